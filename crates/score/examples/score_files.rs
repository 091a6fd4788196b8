//! Scores a tracks CSV against a truth CSV with the default parameters and prints the
//! summary: `cargo run -p argus-score --example score_files -- TRACKS TRUTH`.

use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let [_, tracks, truth] = args.as_slice() else {
        return Err("usage: score_files TRACKS TRUTH".into());
    };
    let tracks = argus_score::read_tracks(Path::new(tracks))?;
    let truth = argus_score::read_truth(Path::new(truth))?;
    let scorer = argus_score::Scorer::new(argus_score::ScoreConfig::default())?;
    let t0 = std::time::Instant::now();
    let score = scorer.score(&tracks, &truth)?;
    let dt = t0.elapsed();
    println!("{:#?}", score.summary);
    println!("scored in {:.3} ms", dt.as_secs_f64() * 1e3);
    Ok(())
}
