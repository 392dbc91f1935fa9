//! Plots that draw no more points than they have pixels: time series are
//! thinned to the first, lowest, highest and last point of each pixel column
//! (peaks survive), paths to points at least a pixel apart. The curves an
//! author shapes are drawn by the graph pane (`ui::graph`).

/// Named series of (x, y) points, each sorted by x.
pub type Series = Vec<(String, Vec<[f64; 2]>)>;

/// The colour of the `index`th series (golden-ratio hues, as egui_plot's own).
pub fn series_color(index: usize) -> egui::Color32 {
    let golden_ratio = (5.0_f32.sqrt() - 1.0) / 2.0;
    // Series counts are small: exact in f32.
    #[allow(clippy::cast_precision_loss)]
    let hue = (index as f32 * golden_ratio).fract();
    egui::ecolor::Hsva::new(hue, 0.85, 0.6, 1.0).into()
}

/// An x-sorted series thinned for `columns` pixel columns across
/// `x_min..=x_max`: per column its first, lowest, highest and last point, in
/// order. Points outside that range are thinned as one column on each side,
/// so the series keeps its extent (a plot that fits its bounds to the data
/// still sees all of it).
pub fn decimate(points: &[[f64; 2]], x_min: f64, x_max: f64, columns: usize) -> Vec<[f64; 2]> {
    let columns = columns.max(1);
    if points.len() <= 4 * columns || x_max.is_nan() || x_min.is_nan() || x_max <= x_min {
        return points.to_vec();
    }
    let scale = columns as f64 / (x_max - x_min);
    let bucket = |x: f64| -> i64 {
        if x < x_min {
            -1
        } else if x > x_max {
            i64::MAX
        } else {
            // Truncation is the point: a column per pixel.
            #[allow(clippy::cast_possible_truncation)]
            let column = ((x - x_min) * scale) as i64;
            column
        }
    };
    let mut out = Vec::with_capacity(4 * columns + 8);
    let flush = |picked: &mut [usize; 4], out: &mut Vec<[f64; 2]>| {
        picked.sort_unstable();
        let mut last = None;
        for &index in picked.iter() {
            if last != Some(index) {
                out.push(points[index]);
                last = Some(index);
            }
        }
    };
    let mut current = bucket(points[0][0]);
    // first, lowest, highest, last
    let mut picked = [0usize; 4];
    for (index, point) in points.iter().enumerate().skip(1) {
        let at = bucket(point[0]);
        if at != current {
            flush(&mut picked, &mut out);
            current = at;
            picked = [index; 4];
            continue;
        }
        if point[1] < points[picked[1]][1] {
            picked[1] = index;
        }
        if point[1] > points[picked[2]][1] {
            picked[2] = index;
        }
        picked[3] = index;
    }
    flush(&mut picked, &mut out);
    out
}

/// A path thinned to points at least a pixel apart (`units_per_pixel` for x
/// and y); its first and last points are always kept.
pub fn thin_path(points: impl IntoIterator<Item = [f64; 2]>, units_per_pixel: [f64; 2]) -> Vec<[f64; 2]> {
    let mut out: Vec<[f64; 2]> = Vec::new();
    let mut pending = None;
    for point in points {
        match out.last() {
            Some(kept)
                if (point[0] - kept[0]).abs() < units_per_pixel[0]
                    && (point[1] - kept[1]).abs() < units_per_pixel[1] =>
            {
                pending = Some(point);
            }
            _ => {
                out.push(point);
                pending = None;
            }
        }
    }
    out.extend(pending);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_series_is_thinned_to_four_points_a_column_and_keeps_its_peaks_and_ends() {
        let points: Vec<[f64; 2]> =
            (0..10_000).map(|i| [f64::from(i), if i == 4321 { 99.0 } else { f64::from(i % 7) }]).collect();
        let thinned = decimate(&points, 0.0, 9_999.0, 100);
        assert!(thinned.len() <= 4 * 101, "{} points", thinned.len());
        assert_eq!(thinned.first(), points.first());
        assert_eq!(thinned.last(), points.last());
        assert!(thinned.contains(&[4321.0, 99.0]), "the peak survives");
        assert!(thinned.windows(2).all(|pair| pair[0][0] < pair[1][0]), "still in x order");
        let lowest = thinned.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        assert_eq!(lowest, 0.0);
    }

    #[test]
    fn points_outside_the_view_keep_the_series_extent() {
        let points: Vec<[f64; 2]> = (0..10_000).map(|i| [f64::from(i), f64::from(i % 100)]).collect();
        let thinned = decimate(&points, 4_000.0, 5_000.0, 50);
        assert!(thinned.len() <= 4 * 52, "{} points", thinned.len());
        assert_eq!(thinned.first(), points.first());
        assert_eq!(thinned.last(), points.last());
        let (low, high) = thinned.iter().fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p[1]), h.max(p[1])));
        assert_eq!((low, high), (0.0, 99.0));
    }

    #[test]
    fn short_series_are_drawn_as_they_are() {
        let points = vec![[0.0, 1.0], [1.0, 5.0], [2.0, -3.0]];
        assert_eq!(decimate(&points, 0.0, 2.0, 400), points);
        assert_eq!(decimate(&points, 0.0, 0.0, 400), points);
    }

    #[test]
    fn a_path_keeps_points_a_pixel_apart_and_its_ends() {
        // A circle of 100,000 points, 1 m across, on a 200-pixel plot.
        let points: Vec<[f64; 2]> = (0..100_000)
            .map(|i| {
                let angle = f64::from(i) * std::f64::consts::TAU / 100_000.0;
                [angle.cos() * 0.5, angle.sin() * 0.5]
            })
            .collect();
        let thinned = thin_path(points.iter().copied(), [1.0 / 200.0, 1.0 / 200.0]);
        assert!(thinned.len() < 1_000, "{} points", thinned.len());
        assert!(thinned.len() > 100, "{} points", thinned.len());
        assert_eq!(thinned.first(), points.first());
        assert_eq!(thinned.last(), points.last());
    }
}
