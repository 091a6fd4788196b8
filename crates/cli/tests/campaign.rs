//! Campaigns split into shards (`argus run --shards K --shard i`), their merge's checks of
//! the campaign as a whole, and the job files of `argus campaign plan` (issue 22).

// Test helpers outside #[test] functions may unwrap: a failure is a test failure.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;

mod common;
use common::{argus, ok, read};

/// The one-line error of a failing command (exit code 2).
fn fails(args: &[&str], dir: &Path) -> String {
    let o = argus(args, dir);
    assert_eq!(o.status.code(), Some(2), "{args:?} should fail");
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(e.lines().count(), 1, "one message: {e}");
    e
}

fn json(dir: &Path, f: &str) -> serde_json::Value {
    serde_json::from_str(&read(dir, f)).unwrap()
}

#[test]
fn four_shards_of_gimpo_merge_to_the_whole_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for i in ["0", "1", "2", "3"] {
        let out = format!("sh/shard-{i}");
        let o = ok(
            &[
                "run", "gimpo", "--runs", "0..6", "--shards", "4", "--shard", i, "--seed", "2",
                "--out", &out,
            ],
            d,
        );
        assert!(o.contains(&format!("(shard {i} of 4 of runs 0..6)")), "{o}");
    }
    ok(
        &[
            "run", "gimpo", "--runs", "6", "--seed", "2", "--out", "whole",
        ],
        d,
    );
    let o = ok(
        &[
            "merge",
            "gimpo",
            "sh/shard-0",
            "sh/shard-1",
            "sh/shard-2",
            "sh/shard-3",
            "--out",
            "m",
        ],
        d,
    );
    assert!(o.contains("--runs 0..6 (4 files)"), "{o}");
    // Everything in summary.json but the output paths, exactly (no tolerance: the same
    // records reduced in the same order); the per-step CSV and a figure byte for byte.
    let (w, m) = (json(d, "whole/summary.json"), json(d, "m/summary.json"));
    for k in ["scenario", "seed", "runs", "params", "results", "notes"] {
        assert_eq!(w[k], m[k], "{k}");
    }
    assert_eq!(read(d, "whole/per_step.csv"), read(d, "m/per_step.csv"));
    assert_eq!(read(d, "whole/fig6_ratio.svg"), read(d, "m/fig6_ratio.svg"));
    assert_eq!(read(d, "whole/runs/0-6.jsonl"), read(d, "m/runs/0-6.jsonl"));
    // Shard 1 of 4 of 0..6 is runs 1..3 (⌊6·1/4⌋ = 1, ⌊6·2/4⌋ = 3).
    assert!(d.join("sh/shard-1/runs/1-3.jsonl").exists());

    // A missing shard is named, with the fix.
    let e = fails(
        &[
            "merge",
            "gimpo",
            "sh/shard-0",
            "sh/shard-1",
            "sh/shard-3",
            "--out",
            "m2",
        ],
        d,
    );
    assert!(
        e.contains("shard 2 of 4 (runs 3..4) is missing: re-submit index 2"),
        "{e}"
    );
    // A shard given twice too.
    std::fs::create_dir_all(d.join("copy/runs")).unwrap();
    std::fs::copy(
        d.join("sh/shard-1/runs/1-3.jsonl"),
        d.join("copy/runs/1-3.jsonl"),
    )
    .unwrap();
    let e = fails(
        &[
            "merge",
            "gimpo",
            "sh/shard-0",
            "sh/shard-1",
            "copy",
            "sh/shard-2",
            "sh/shard-3",
            "--out",
            "m2",
        ],
        d,
    );
    assert!(e.contains("shard 1 is given twice"), "{e}");
    assert!(
        e.contains("re-submitting index 1 gives identical output"),
        "{e}"
    );
    // A shard of another Argus version is refused, naming the field.
    let f = d.join("sh/shard-3/runs/4-6.jsonl");
    let text = read(d, "sh/shard-3/runs/4-6.jsonl");
    let v = format!("\"argus_version\":\"{}\"", env!("CARGO_PKG_VERSION"));
    assert!(text.contains(&v), "the header names the version");
    std::fs::write(&f, text.replacen(&v, "\"argus_version\":\"0.0.1\"", 1)).unwrap();
    let e = fails(
        &[
            "merge",
            "gimpo",
            "sh/shard-0",
            "sh/shard-1",
            "sh/shard-2",
            "sh/shard-3",
            "--out",
            "m2",
        ],
        d,
    );
    assert!(e.contains("4-6.jsonl:1: field 'argus_version'"), "{e}");
    assert!(!d.join("m2").exists(), "no output left by a failed merge");
}

#[test]
fn shard_options_are_checked() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let e = fails(
        &[
            "run", "cv-polar", "--runs", "3", "--shards", "4", "--shard", "0",
        ],
        d,
    );
    assert!(e.contains("--shards 4: expected 1 ..= 3 shards"), "{e}");
    let e = fails(
        &[
            "run", "cv-polar", "--runs", "8", "--shards", "4", "--shard", "4",
        ],
        d,
    );
    assert!(e.contains("--shard 4: expected an index in 0..4"), "{e}");
}

/// The `(start, end)` a plan's shard script prints for `SLURM_ARRAY_TASK_ID = i`, read by
/// running its range line in bash.
fn script_range(script: &str, i: u64) -> (u64, u64) {
    let line = script
        .lines()
        .find(|l| l.starts_with("start=$(("))
        .expect("the script computes the range");
    let o = std::process::Command::new("bash")
        .arg("-c")
        .arg(format!("i={i}; {line}; echo $start $end"))
        .output()
        .unwrap();
    let s = String::from_utf8_lossy(&o.stdout);
    let v: Vec<u64> = s.split_whitespace().map(|x| x.parse().unwrap()).collect();
    (v[0], v[1])
}

#[test]
fn plan_writes_slurm_and_kubernetes_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = ok(
        &[
            "campaign",
            "plan",
            "gimpo",
            "--runs",
            "0..10",
            "--shards",
            "4",
            "--set",
            "sigma_r=60",
            "--out",
            "plan",
            "--argus",
            "/opt/argus bin/argus",
        ],
        d,
    );
    assert!(o.contains("submit.sh"), "prints how to submit: {o}");
    assert!(o.contains("re-submit index i"), "{o}");
    // Every script is `bash -n` clean.
    for f in ["shard.sbatch", "merge.sbatch", "submit.sh", "k8s/submit.sh"] {
        let st = std::process::Command::new("bash")
            .arg("-n")
            .arg(d.join("plan").join(f))
            .status()
            .unwrap();
        assert!(st.success(), "bash -n {f}");
    }
    let shard = read(d, "plan/shard.sbatch");
    assert!(shard.contains("#SBATCH --array=0-3\n"), "{shard}");
    assert!(shard.contains("--shards 4 --shard \"$i\""), "{shard}");
    assert!(shard.contains("--set sigma_r=60"), "{shard}");
    assert!(
        shard.contains("'/opt/argus bin/argus' run gimpo --runs 0..10"),
        "quoted: {shard}"
    );
    // The 4 shard ranges the script prints cover 0..10 exactly once, as argus cuts them.
    let mut next = 0;
    for i in 0..4 {
        let (a, b) = script_range(&shard, i);
        assert_eq!(a, next, "shard {i} starts where the last ended");
        assert!(b > a, "shard {i} is not empty");
        next = b;
    }
    assert_eq!(next, 10, "the last shard ends the campaign");
    let submit = read(d, "plan/submit.sh");
    assert!(
        submit.contains("sbatch --parsable shard.sbatch"),
        "{submit}"
    );
    assert!(
        submit.contains("--dependency=afterok:\"$array\" merge.sbatch"),
        "{submit}"
    );
    let merge = read(d, "plan/merge.sbatch");
    assert!(merge.contains(" merge gimpo "), "{merge}");
    // The Kubernetes Indexed Job, checked structurally (no YAML parser among the
    // dependencies): the keys at their indentation, the shard from the completion index.
    let job = read(d, "plan/k8s/shards-job.yaml");
    for want in [
        "\nkind: Job\n",
        "\n  completionMode: Indexed\n",
        "\n  completions: 4\n",
        "\n      restartPolicy: Never\n",
        "--shard \\\"$JOB_COMPLETION_INDEX\\\"",
        "/shared/shard-\\\"$JOB_COMPLETION_INDEX\\\"",
    ] {
        assert!(job.contains(want), "missing {want:?} in {job}");
    }
    let merge_job = read(d, "plan/k8s/merge-job.yaml");
    assert!(
        merge_job.contains("argus merge gimpo /shared/shard-* --out /shared/merged"),
        "{merge_job}"
    );
    for (name, y) in [("shards", &job), ("merge", &merge_job)] {
        assert!(!y.contains('\t'), "{name}: no tabs in YAML");
        for l in y
            .lines()
            .filter(|l| !l.trim_start().starts_with('#') && !l.trim().is_empty())
        {
            let indent = l.len() - l.trim_start().len();
            assert_eq!(indent % 2, 0, "{name}: two-space indentation: {l:?}");
        }
    }
    // Where a YAML parser is at hand (Python's), the manifests must load and hold the fields.
    let py = "import sys, yaml\nj = yaml.safe_load(open(sys.argv[1]))\ns = j['spec']\nassert j['kind'] == 'Job' and s['completionMode'] == 'Indexed' and s['completions'] == 4, s\nc = s['template']['spec']['containers'][0]\nassert 'JOB_COMPLETION_INDEX' in c['args'][0], c\nyaml.safe_load(open(sys.argv[2]))\n";
    let have_yaml = std::process::Command::new("python3")
        .args(["-c", "import yaml"])
        .output()
        .is_ok_and(|o| o.status.success());
    {
        if have_yaml {
            let st = std::process::Command::new("python3")
                .args(["-c", py])
                .arg(d.join("plan/k8s/shards-job.yaml"))
                .arg(d.join("plan/k8s/merge-job.yaml"))
                .status()
                .unwrap();
            assert!(st.success(), "the manifests load as YAML with their fields");
        }
    }
    // A plan the runs cannot fill is refused.
    let e = fails(
        &[
            "campaign", "plan", "gimpo", "--runs", "3", "--shards", "4", "--out", "p2",
        ],
        d,
    );
    assert!(e.contains("--shards 4"), "{e}");
}
