//! Grid binning of plot positions, so gating costs tracks × nearby plots.

use argus_core_math::Vector;

/// Plots binned in square cells, stored as `(row, column, plot)` sorted so that each
/// grid row's cells are contiguous; the buffer is reused from scan to scan.
#[derive(Debug, Clone, Default)]
pub(crate) struct Grid {
    cell: f64,
    entries: Vec<(i64, i64, u32)>,
}

impl Grid {
    pub(crate) fn new(cell: f64) -> Self {
        Self {
            cell,
            entries: Vec::new(),
        }
    }

    /// The cell index of a coordinate (saturating for huge values).
    #[allow(clippy::cast_possible_truncation)]
    fn index(&self, v: f64) -> i64 {
        // floor without the libm call (not inlined on the baseline x86-64 target):
        // truncate, then step down for negative non-integers. Saturating as before.
        let q = v / self.cell;
        let t = q as i64;
        #[allow(clippy::cast_precision_loss)]
        let below = (t as f64) > q;
        t.saturating_sub(i64::from(below))
    }

    /// Bins the positions (their index in the slice is the plot number).
    pub(crate) fn rebuild(&mut self, positions: impl Iterator<Item = Vector<2>>) {
        self.entries.clear();
        for (k, p) in positions.enumerate() {
            let k = u32::try_from(k).unwrap_or(u32::MAX);
            self.entries.push((self.index(p[1]), self.index(p[0]), k));
        }
        self.entries.sort_unstable();
    }

    /// Calls `f` with every plot whose cell meets the box `centre ± half`.
    pub(crate) fn query(&self, centre: &Vector<2>, half: [f64; 2], mut f: impl FnMut(usize)) {
        if self.entries.is_empty() {
            return;
        }
        let (x0, x1) = (
            self.index(centre[0] - half[0]),
            self.index(centre[0] + half[0]),
        );
        let (y0, y1) = (
            self.index(centre[1] - half[1]),
            self.index(centre[1] + half[1]),
        );
        let rows = y1.saturating_sub(y0).saturating_add(1);
        // A box spanning more rows than there are plots: a linear scan is cheaper.
        if rows > i64::try_from(self.entries.len()).unwrap_or(i64::MAX) {
            for &(y, x, k) in &self.entries {
                if (y0..=y1).contains(&y) && (x0..=x1).contains(&x) {
                    f(k as usize);
                }
            }
            return;
        }
        for y in y0..=y1 {
            let start = self.entries.partition_point(|e| (e.0, e.1) < (y, x0));
            for &(ey, ex, k) in &self.entries[start..] {
                if ey != y || ex > x1 {
                    break;
                }
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
        // Cells of 10 m. Plots at (5,5) cell (0,0); (15,5) cell (0,1); (-5,25) cell (2,-1);
        // (100,100) cell (10,10). A box (0..20, 0..9) meets cells y=0, x=0..2: plots 0, 1.
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
        // A huge box takes the linear-scan path and finds all four.
        let mut all = Vec::new();
        g.query(&Vector::<2>::new(0.0, 0.0), [1e9, 1e9], |k| all.push(k));
        all.sort_unstable();
        assert_eq!(all, vec![0, 1, 2, 3]);
    }
}
