//! Draws a [`Figure`] with plotters (axes labelled with units, legend), as SVG and as
//! PNG. Text is laid out (and, in PNG, rasterised with `ab_glyph`) with DejaVu Sans from
//! the `dejavu` crate (Bitstream Vera / DejaVu font licence: free to embed and
//! redistribute), registered once as `sans-serif`; no system font or library is used.

use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;

use argus_scenarios::{Figure, LineStyle};

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(90, 90, 90),
];

fn bounds(fig: &Figure) -> ((f64, f64), (f64, f64)) {
    let pts = || {
        fig.lines
            .iter()
            .flat_map(|l| l.points.iter())
            .filter(|(x, y)| x.is_finite() && y.is_finite())
    };
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for (x, y) in pts() {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    if !(x0.is_finite() && x1.is_finite()) {
        (x0, x1) = (0.0, 1.0);
    }
    if !(y0.is_finite() && y1.is_finite()) {
        (y0, y1) = (0.0, 1.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
    let y0 = if y0 >= 0.0 {
        0.0f64.max(y0 - pad)
    } else {
        y0 - pad
    };
    ((x0, x1), (y0, y1 + pad))
}

/// Figure size in pixels (SVG user units).
pub(crate) const SIZE: (u32, u32) = (800, 500);

/// Registers DejaVu Sans as plotters' `sans-serif` once.
///
/// # Errors
/// The font bytes do not parse (cannot happen with the shipped font; reported, not
/// panicked).
fn fonts() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .map_err(|_| "DejaVu Sans does not parse as a font".to_owned())?;
        plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold())
            .map_err(|_| "DejaVu Sans Bold does not parse as a font".to_owned())
    })
    .clone()
}

/// Renders `fig` as an SVG document.
///
/// # Errors
/// plotters' drawing error, as text.
pub(crate) fn svg(fig: &Figure) -> Result<String, String> {
    fonts()?;
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, SIZE).into_drawing_area();
        draw(&root, fig)?;
    }
    Ok(buf)
}

/// Renders `fig` as a PNG image (8-bit RGB).
///
/// # Errors
/// plotters' drawing error or the PNG encoder's, as text.
pub(crate) fn png(fig: &Figure) -> Result<Vec<u8>, String> {
    fonts()?;
    let (w, h) = SIZE;
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, fig)?;
    }
    let mut out = Vec::new();
    {
        let mut enc = ::png::Encoder::new(&mut out, w, h);
        enc.set_color(::png::ColorType::Rgb);
        enc.set_depth(::png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(&rgb).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// Draws `fig` on `root` (any plotters backend).
fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, fig: &Figure) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let ((x0, x1), (y0, y1)) = bounds(fig);
    let mut chart = ChartBuilder::on(root)
        .caption(&fig.title, ("sans-serif", 20))
        .margin(12)
        // Room for the last x tick label, centred on the right edge.
        .margin_right(30)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(&fig.x_label)
        .y_desc(&fig.y_label)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, line) in fig.lines.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let pts: Vec<(f64, f64)> = line
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        // The legend sample is drawn like the line it names.
        let legend_style = match line.style {
            LineStyle::Bound => color.mix(0.6).stroke_width(1),
            LineStyle::Solid | LineStyle::Points => color.stroke_width(2),
        };
        match line.style {
            LineStyle::Solid => chart
                .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                .map_err(|e| e.to_string())?,
            LineStyle::Bound => chart
                .draw_series(LineSeries::new(pts, color.mix(0.6).stroke_width(1)))
                .map_err(|e| e.to_string())?,
            LineStyle::Points => chart
                .draw_series(pts.into_iter().map(|p| Circle::new(p, 2, color.filled())))
                .map_err(|e| e.to_string())?,
        }
        .label(line.label.clone())
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], legend_style));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())?;
    Ok(())
}
