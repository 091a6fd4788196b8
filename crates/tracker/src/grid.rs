//! Grid binning of plot positions, so gating costs tracks × nearby plots.

use argus_core_math::Vector;

/// Plots binned in square cells over the bounding box of the scan's plots, in a dense
/// table built by a counting sort (`O(plots + cells)`, no comparison sort): the plots of
/// cell `c` are `plots[starts[c]..starts[c + 1]]`, in increasing plot index. A query
/// visits the cells met by a box row by row, column by column, so it reports plots in
/// the order `(row, column, plot)`. The buffers are reused from scan to scan.
///
/// When the plots are spread so thinly that the table would have more than
/// `max(4 × plots, 4096)` cells, the cell side is doubled until it fits: a coarser
/// cell only makes a query report more candidates (the chi-square gate decides), never
/// fewer, so correctness does not depend on the cell size.
#[derive(Debug, Clone, Default)]
pub(crate) struct Grid {
    /// The configured cell side (m).
    cell: f64,
    /// The cell side used for the current table (≥ `cell`).
    side: f64,
    /// Lower-left corner of the table (m).
    origin: [f64; 2],
    /// Table size in columns (x) and rows (y).
    nx: usize,
    ny: usize,
    /// Cell start offsets into `plots` (`nx · ny + 1` entries).
    starts: Vec<u32>,
    /// Plot indices ordered by cell.
    plots: Vec<u32>,
    /// Scratch: each plot's cell.
    cells: Vec<u32>,
    /// Scratch: the positions of the current scan.
    points: Vec<[f64; 2]>,
}

impl Grid {
    /// A grid with square cells of side `cell` (m, finite and positive: validated by
    /// the tracker configuration).
    pub(crate) fn new(cell: f64) -> Self {
        Self {
            cell,
            side: cell,
            ..Self::default()
        }
    }

    /// `floor((v − origin) / side)` clamped to `[0, n − 1]` as a signed cell index
    /// (negative or ≥ n when outside: the caller clamps after comparing).
    #[allow(clippy::cast_possible_truncation)]
    fn index(&self, v: f64, origin: f64) -> i64 {
        // floor without the libm call (not inlined on the baseline x86-64 target):
        // truncate, then step down for negative non-integers. `as` saturates.
        let q = (v - origin) / self.side;
        let t = q as i64;
        #[allow(clippy::cast_precision_loss)]
        let below = (t as f64) > q;
        t.saturating_sub(i64::from(below))
    }

    /// Bins the scan's plot positions (plot `k` is the `k`-th item).
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    pub(crate) fn rebuild(&mut self, positions: impl Iterator<Item = Vector<2>>) {
        self.points.clear();
        self.points.extend(positions.map(|p| [p[0], p[1]]));
        let n = self.points.len();
        self.plots.clear();
        self.cells.clear();
        self.starts.clear();
        self.side = self.cell;
        if n == 0 {
            self.nx = 0;
            self.ny = 0;
            return;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &self.points {
            for a in 0..2 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        self.origin = lo;
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        let limit = (4 * n).max(4096) as f64;
        if w.is_finite() && h.is_finite() {
            while (w / self.side + 1.0).floor() * (h / self.side + 1.0).floor() > limit {
                self.side *= 2.0;
            }
            self.nx = (w / self.side) as usize + 1;
            self.ny = (h / self.side) as usize + 1;
        } else {
            // Extents beyond f64's range: one cell holds everything.
            self.side = f64::INFINITY;
            self.nx = 1;
            self.ny = 1;
        }
        let (nx, ny) = (self.nx, self.ny);
        self.starts.resize(nx * ny + 1, 0);
        for k in 0..n {
            let p = self.points[k];
            let cx = (self.index(p[0], self.origin[0]).max(0) as usize).min(nx - 1);
            let cy = (self.index(p[1], self.origin[1]).max(0) as usize).min(ny - 1);
            let c = cy * nx + cx;
            self.cells.push(c as u32);
            self.starts[c + 1] += 1;
        }
        for c in 0..nx * ny {
            self.starts[c + 1] += self.starts[c];
        }
        // Fill in plot order, so each cell lists its plots increasingly; `cursor` reuses
        // the scratch of cell ids: after the fill, `starts` is restored below.
        self.plots.resize(n, 0);
        for k in 0..n {
            let c = self.cells[k] as usize;
            let slot = self.starts[c] as usize;
            self.plots[slot] = u32::try_from(k).unwrap_or(u32::MAX);
            self.starts[c] += 1;
        }
        // Each `starts[c]` now holds the end of cell c: shift back by one cell.
        for c in (1..=nx * ny).rev() {
            self.starts[c] = self.starts[c - 1];
        }
        self.starts[0] = 0;
    }

    /// Calls `f` with every plot in a cell met by the box `centre ± half`.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    pub(crate) fn query(&self, centre: &Vector<2>, half: [f64; 2], mut f: impl FnMut(usize)) {
        if self.nx == 0 {
            return;
        }
        let clamp = |lo: i64, hi: i64, n: usize| -> Option<(usize, usize)> {
            let last = i64::try_from(n - 1).unwrap_or(i64::MAX);
            if hi < 0 || lo > last {
                return None;
            }
            Some((lo.max(0) as usize, hi.min(last) as usize))
        };
        let Some((x0, x1)) = clamp(
            self.index(centre[0] - half[0], self.origin[0]),
            self.index(centre[0] + half[0], self.origin[0]),
            self.nx,
        ) else {
            return;
        };
        let Some((y0, y1)) = clamp(
            self.index(centre[1] - half[1], self.origin[1]),
            self.index(centre[1] + half[1], self.origin[1]),
            self.ny,
        ) else {
            return;
        };
        for y in y0..=y1 {
            let row = y * self.nx;
            let (a, b) = (
                self.starts[row + x0] as usize,
                self.starts[row + x1 + 1] as usize,
            );
            for &k in &self.plots[a..b] {
                f(k as usize);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn query_finds_exactly_the_plots_in_the_cells_met() {
        // Cells of 10 m from the lower-left plot (-5, 5). Plots at (5,5) → cell
        // (row 0, col 1); (15,5) → (0, 2); (-5,25) → (2, 0); (100,100) → (9, 10). The box
        // (0..20, 0..9) meets row 0 (clamped from -1), columns 0..2: plots 0 and 1.
        let mut g = Grid::new(10.0);
        let pts = [
            Vector::<2>::new(5.0, 5.0),
            Vector::<2>::new(15.0, 5.0),
            Vector::<2>::new(-5.0, 25.0),
            Vector::<2>::new(100.0, 100.0),
        ];
        g.rebuild(pts.iter().copied());
        let mut found = Vec::new();
        g.query(&Vector::<2>::new(10.0, 4.5), [10.0, 4.5], |k| found.push(k));
        found.sort_unstable();
        assert_eq!(found, vec![0, 1]);
        // A huge box finds all four.
        let mut all = Vec::new();
        g.query(&Vector::<2>::new(0.0, 0.0), [1e9, 1e9], |k| all.push(k));
        all.sort_unstable();
        assert_eq!(all, vec![0, 1, 2, 3]);
    }

    /// The brute-force answer: plots whose cell (at the grid's side and origin) meets
    /// the box's cells.
    fn brute(g: &Grid, pts: &[Vector<2>], c: &Vector<2>, half: [f64; 2]) -> Vec<usize> {
        let cell = |v: f64, o: f64| ((v - o) / g.side).floor();
        let mut out: Vec<usize> = (0..pts.len())
            .filter(|&k| {
                let (x, y) = (pts[k][0], pts[k][1]);
                let (cx, cy) = (cell(x, g.origin[0]), cell(y, g.origin[1]));
                cx >= cell(c[0] - half[0], g.origin[0]).max(0.0)
                    && cx <= cell(c[0] + half[0], g.origin[0])
                    && cy >= cell(c[1] - half[1], g.origin[1]).max(0.0)
                    && cy <= cell(c[1] + half[1], g.origin[1])
            })
            .collect();
        out.sort_unstable();
        out
    }

    proptest::proptest! {
        #[test]
        fn query_equals_brute_force_and_is_ordered(
            raw in proptest::collection::vec((-5e4f64..5e4, -5e4f64..5e4), 1..60),
            cx in -6e4f64..6e4, cy in -6e4f64..6e4, hx in 0.0f64..2e4, hy in 0.0f64..2e4,
            cell in 100.0f64..5000.0,
        ) {
            let pts: Vec<Vector<2>> = raw.iter().map(|&(x, y)| Vector::<2>::new(x, y)).collect();
            let mut g = Grid::new(cell);
            g.rebuild(pts.iter().copied());
            let c = Vector::<2>::new(cx, cy);
            let mut found = Vec::new();
            g.query(&c, [hx, hy], |k| found.push(k));
            // Within one cell the plots come in increasing index; across cells in
            // (row, column) order: sorting the found set must equal the brute force.
            let mut sorted = found.clone();
            sorted.sort_unstable();
            proptest::prop_assert_eq!(sorted, brute(&g, &pts, &c, [hx, hy]));
            // Every plot lies in exactly one cell: a box over everything finds each once.
            let mut all = Vec::new();
            g.query(&Vector::<2>::zeros(), [1e6, 1e6], |k| all.push(k));
            all.sort_unstable();
            proptest::prop_assert_eq!(all, (0..pts.len()).collect::<Vec<_>>());
        }
    }

    #[test]
    fn sparse_plots_coarsen_the_table_and_extreme_ones_share_one_cell() {
        // Two plots 1e7 m apart with 1 m cells would need 1e14 cells: the side doubles
        // until the table has at most 4096 cells.
        let mut g = Grid::new(1.0);
        let pts = [Vector::<2>::new(0.0, 0.0), Vector::<2>::new(1e7, 1e7)];
        g.rebuild(pts.iter().copied());
        assert!(g.nx * g.ny <= 4096 && g.side > 1.0);
        let mut found = Vec::new();
        g.query(&Vector::<2>::new(1e7, 1e7), [0.5, 0.5], |k| found.push(k));
        assert!(found.contains(&1));
        // Extents past f64's range (finite plots at ±1e308).
        let mut h = Grid::new(1.0);
        let far = [Vector::<2>::new(-1e308, 0.0), Vector::<2>::new(1e308, 0.0)];
        h.rebuild(far.iter().copied());
        let mut both = Vec::new();
        h.query(&Vector::<2>::new(0.0, 0.0), [1.0, 1.0], |k| both.push(k));
        assert_eq!(both, vec![0, 1]);
    }
}
