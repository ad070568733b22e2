//! Heights under points, in metres: what a height scanner or a foothold
//! planner reads from the terrain.

use crate::terrain::Terrain;

impl Terrain {
    /// The top under the point `(x, y)` (metres, the terrain's frame: cell
    /// `(i, j)` covers `[i·s, (i+1)·s] × [j·s, (j+1)·s]`), or `None` off
    /// the terrain. On an edge or corner shared by cells, the highest of
    /// them: where a foot set there rests. Over a ramp, its plane where it
    /// is above the cells (the staircase it leaves in the heightmap lies
    /// under it).
    ///
    /// ```
    /// let scheme = rse_core::Scheme::from_csv("# size: 5x5\ntype,height,angle,x1,y1\npeak,2,45,2,2\n", None)?;
    /// let terrain = rse_core::generate(&scheme, 0, 0);
    /// assert_eq!(terrain.height_at(0.25, 0.25), Some(0.2)); // cell (2, 2): 2 steps of 0.1 m
    /// assert_eq!(terrain.height_at(0.2, 0.2), Some(0.2)); // its corner
    /// assert_eq!(terrain.height_at(0.05, 0.05), Some(0.0));
    /// assert_eq!(terrain.height_at(-0.01, 0.05), None);
    /// # Ok::<(), rse_core::SchemeError>(())
    /// ```
    pub fn height_at(&self, x: f64, y: f64) -> Option<f64> {
        let s = self.block_size();
        let grid = self.grid();
        let (u, v) = (x / s, y / s);
        let cells = |t: f64, n: u32| -> Option<(u32, u32)> {
            if !(0.0..=f64::from(n)).contains(&t) {
                return None;
            }
            // A point on a line between cells touches both.
            let lo = (t.ceil() - 1.0).max(0.0);
            let hi = t.floor().min(f64::from(n) - 1.0);
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // in 0..n
            Some((lo as u32, hi as u32))
        };
        let (x_lo, x_hi) = cells(u, grid.nx)?;
        let (y_lo, y_hi) = cells(v, grid.ny)?;
        let map = self.heightmap();
        let top = (y_lo..=y_hi)
            .flat_map(|j| (x_lo..=x_hi).map(move |i| map.get(i, j)))
            .max()?;
        let cells = self.base() + f64::from(top) * self.step_height();
        let touched = |r: &&crate::Ramp| {
            let [x0, y0, x1, y1] = r.cells;
            x0 <= x_hi && x_lo <= x1 && y0 <= y_hi && y_lo <= y1
        };
        let planes = self
            .ramps()
            .iter()
            .filter(touched)
            .map(|r| r.height_at(u, v, self.base(), self.step_height()));
        Some(planes.fold(cells, f64::max))
    }
}

#[cfg(test)]
mod tests {
    use crate::{Scheme, generate};

    #[test]
    fn every_point_of_a_cell_reads_its_top_and_edges_read_the_higher() {
        let scheme = Scheme::from_csv(
            "# size: 4x3\n# base: 0.05\ntype,height,angle,x1,y1\npeak,3,90,1,1\n",
            None,
        )
        .unwrap();
        let t = generate(&scheme, 0, 0);
        let top = |x, y| t.height_at(x, y).map(|z| (z * 1e9).round() / 1e9);
        assert_eq!(top(0.15, 0.15), Some(0.35));
        assert_eq!(top(0.101, 0.199), Some(0.35));
        assert_eq!(top(0.05, 0.15), Some(0.05));
        assert_eq!(top(0.1, 0.15), Some(0.35), "edge of the peak");
        assert_eq!(top(0.0, 0.0), Some(0.05), "outer corner");
        assert_eq!(top(0.4, 0.3), Some(0.05), "far corner");
        assert_eq!(top(0.4001, 0.1), None);
        assert_eq!(top(0.1, f64::NAN), None);
    }

    #[test]
    fn over_a_ramp_a_point_reads_its_plane() {
        // 4 cells climbing 2 steps of 0.1 m along x from x = 0.1.
        let scheme = Scheme::from_csv(
            "# size: 6x2\ntype,height,angle,x1,y1,x2,y2\nramp,2,,1,0,4,1\n",
            None,
        )
        .unwrap();
        let t = generate(&scheme, 0, 0);
        let top = |x, y| t.height_at(x, y).map(|z| (z * 1e9).round() / 1e9);
        assert_eq!(top(0.1, 0.1), Some(0.0), "its foot");
        assert_eq!(top(0.3, 0.05), Some(0.1), "halfway");
        assert_eq!(top(0.45, 0.15), Some(0.175));
        assert_eq!(top(0.5, 0.15), Some(0.2), "its top edge, beside the ground");
        assert_eq!(top(0.55, 0.15), Some(0.0), "past it");
    }
}
