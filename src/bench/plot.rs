//! Log-log line plots written as SVG with plotters: the benchmarks' `--plot`.

use plotters::prelude::*;
use std::path::Path;

/// One line of a panel.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub name: String,
    /// `(x, y)` points, both > 0 (drawn in order).
    pub points: Vec<(f64, f64)>,
}

/// One chart of the figure.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// The lines.
    pub series: Vec<Series>,
}

/// Axis labels shared by every panel.
#[derive(Debug, Clone, Copy)]
pub struct Axes<'a> {
    /// Label of the horizontal axis.
    pub x: &'a str,
    /// Label of the vertical axis.
    pub y: &'a str,
    /// The legend in the lower left corner instead of the upper right.
    pub legend_lower_left: bool,
}

/// A tick label: plain digits from 0.01 to 9999, else mantissa and exponent.
fn tick(v: f64) -> String {
    let a = v.abs();
    if (1.0..1e4).contains(&a) {
        format!("{v:.0}")
    } else if (0.01..1.0).contains(&a) {
        format!("{v:.2}")
    } else {
        format!("{v:.0e}")
    }
}

/// The range of the positive, finite values in `vals`, widened by a factor 1.5 each
/// way (a factor 10 when there is one value).
fn log_range(vals: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = vals
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return 0.1..10.0;
    }
    if lo == hi {
        return lo / 10.0..hi * 10.0;
    }
    lo / 1.5..hi * 1.5
}

/// Writes panels side by side as one SVG, both axes logarithmic. Points that are not
/// positive and finite (an error of exactly 0, a blown-up run) are left out.
///
/// # Errors
/// When the file cannot be written.
pub fn log_log_svg(path: &Path, panels: &[Panel], axes: Axes) -> anyhow::Result<()> {
    let width = 620 * u32::try_from(panels.len().max(1))?;
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, (width, 520)).into_drawing_area();
    let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
        root.fill(&WHITE)?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (area, panel) in areas.iter().zip(panels) {
            let good =
                |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0;
            let all = || {
                panel
                    .series
                    .iter()
                    .flat_map(|s| s.points.iter().filter(good))
            };
            let xs = log_range(all().map(|p| p.0));
            let ys = log_range(all().map(|p| p.1));
            let mut chart = ChartBuilder::on(area)
                .caption(&panel.title, ("sans-serif", 20))
                .margin(12)
                .x_label_area_size(44)
                .y_label_area_size(64)
                .build_cartesian_2d(xs.log_scale(), ys.log_scale())?;
            chart
                .configure_mesh()
                .x_desc(axes.x)
                .y_desc(axes.y)
                .x_labels(8)
                .y_labels(10)
                .x_label_formatter(&|v| tick(*v))
                .y_label_formatter(&|v| tick(*v))
                .draw()?;
            for (i, s) in panel.series.iter().enumerate() {
                let colour = Palette99::pick(i).to_rgba();
                let pts: Vec<(f64, f64)> = s.points.iter().filter(good).copied().collect();
                chart
                    .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))?
                    .label(s.name.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
            }
            chart
                .configure_series_labels()
                .position(if axes.legend_lower_left {
                    SeriesLabelPosition::LowerLeft
                } else {
                    SeriesLabelPosition::UpperRight
                })
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    drop(root);
    // Whole or not at all, as every picture we write.
    crate::export::write_all(path, svg.as_bytes())?;
    Ok(())
}

/// The most lines [`line_svg`] labels in a legend.
const MOST_LABELLED: usize = 12;

/// Writes one chart of lines on linear axes (from 0) as SVG, no markers: long
/// time series such as `bench rocking`'s amplitudes. `labels`: (x, y) axis labels.
///
/// # Errors
/// When the file cannot be written.
pub fn line_svg(
    path: &Path,
    title: &str,
    series: &[Series],
    labels: (&str, &str),
) -> anyhow::Result<()> {
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all = || series.iter().flat_map(|s| s.points.iter().filter(finite));
    let x_max = all().map(|p| p.0).fold(0.0_f64, f64::max).max(1e-9);
    let y_max = all().map(|p| p.1).fold(0.0_f64, f64::max).max(1e-9) * 1.05;
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, (900, 520)).into_drawing_area();
    let draw = || -> Result<(), Box<dyn std::error::Error + '_>> {
        root.fill(&WHITE)?;
        // Past a dozen lines a legend would run off the picture (200 balls).
        let legend = series.len() <= MOST_LABELLED;
        let caption = if legend {
            title.to_owned()
        } else {
            format!("{title} ({} lines, too many to label)", series.len())
        };
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(0.0..x_max, 0.0..y_max)?;
        chart
            .configure_mesh()
            .x_desc(labels.0)
            .y_desc(labels.1)
            .draw()?;
        for (i, s) in series.iter().enumerate() {
            let colour = Palette99::pick(i).to_rgba();
            let pts: Vec<(f64, f64)> = s.points.iter().filter(finite).copied().collect();
            let drawn = chart.draw_series(LineSeries::new(pts, colour.stroke_width(2)))?;
            if legend {
                drawn.label(s.name.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
        if legend {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()?;
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    drop(root);
    crate::export::write_all(path, svg.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{Series, line_svg};

    /// `n` lines named `ball 1`.. into an SVG; its text.
    fn lines_svg(n: usize) -> String {
        let dir = std::env::temp_dir().join(format!("nc-plot-{n}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("lines.svg");
        let series: Vec<Series> = (0..n)
            .map(|i| Series {
                name: format!("ball {}", i + 1),
                points: vec![(0.0, i as f64), (1.0, 1.0 + i as f64)],
            })
            .collect();
        line_svg(&path, "Amplitude", &series, ("t", "a")).expect("written");
        let text = std::fs::read_to_string(&path).expect("read");
        std::fs::remove_dir_all(&dir).ok();
        text
    }

    #[test]
    fn a_dozen_lines_get_a_legend_and_two_hundred_do_not() {
        let few = lines_svg(5);
        assert!(
            few.contains("ball 5") && !few.contains("too many"),
            "labelled"
        );
        let many = lines_svg(200);
        assert!(many.contains("200 lines, too many to label"));
        assert!(
            !many.contains("ball 1<") && !many.contains("ball 200"),
            "no legend"
        );
    }
}
