//! A ramp's closed wedge: the solid under its plane, from the ground up,
//! over its rectangle; a shell of its own beside the blocks' (docs/meshes.md,
//! "Ramps").

use super::MeshUnits;
use super::faces::{LatticePoint, Normal};
use crate::ramp::Ramp;

/// Where a local face's outward normal points: along the climb `u`, across
/// it `v`, up or down, or the plane.
#[derive(Clone, Copy)]
enum Facing {
    /// −u: the foot's face (only over a slab).
    Foot,
    /// +u: the top edge's face.
    Head,
    /// −v
    Right,
    /// +v
    Left,
    /// −z
    Bottom,
    /// The plane.
    Plane,
}

/// A shell: lattice points, triangles counter-clockwise seen from outside,
/// and each triangle's normal.
pub(crate) type Shell = (Vec<LatticePoint>, Vec<[u32; 3]>, Vec<Normal>);

/// The wedge of `ramp`. `None` for a ramp of no rise (the slab's cells
/// already cover a flat one).
pub(crate) fn wedge(ramp: &Ramp, units: MeshUnits) -> Option<Shell> {
    if ramp.rise == 0 {
        return None;
    }
    let [x0, y0, x1, y1] = ramp.cells;
    let (run, width) = if ramp.along_y {
        (y1 - y0 + 1, x1 - x0 + 1)
    } else {
        (x1 - x0 + 1, y1 - y0 + 1)
    };
    let (foot, top) = (units.top_level(0), units.top_level(ramp.rise as u16));
    let slab = foot > 0;
    // Local corners (u along the climb from the foot edge, v across, level).
    let mut local: Vec<[u32; 3]> = vec![
        [0, 0, 0],
        [run, 0, 0],
        [run, width, 0],
        [0, width, 0],
        [run, 0, top],
        [run, width, top],
    ];
    let (f0, f3) = if slab {
        local.extend([[0, 0, foot], [0, width, foot]]);
        (6, 7)
    } else {
        (0, 3)
    };
    let mut faces: Vec<([u32; 3], Facing)> = vec![
        ([0, 3, 2], Facing::Bottom),
        ([0, 2, 1], Facing::Bottom),
        ([1, 2, 5], Facing::Head),
        ([1, 5, 4], Facing::Head),
        ([0, 1, 4], Facing::Right),
        ([3, 5, 2], Facing::Left),
        ([f0, 4, 5], Facing::Plane),
        ([f0, 5, f3], Facing::Plane),
    ];
    if slab {
        faces.extend([
            ([0, 6, 7], Facing::Foot),
            ([0, 7, 3], Facing::Foot),
            ([0, 4, 6], Facing::Right),
            ([3, 7, 5], Facing::Left),
        ]);
    }
    // Local (u, v) to the grid's (x, y): a mirror when exactly one of
    // "along y" (u and v swapped) and "descending" (u reversed) holds, and
    // a mirror turns each triangle's winding.
    let (hi_x, hi_y) = (x1 + 1, y1 + 1);
    let place = |[u, v, level]: [u32; 3]| -> LatticePoint {
        let u_at = |lo: u32, hi: u32| if ramp.ascending { lo + u } else { hi - u };
        if ramp.along_y {
            [x0 + v, u_at(y0, hi_y), level]
        } else {
            [u_at(x0, hi_x), y0 + v, level]
        }
    };
    let mirrored = ramp.along_y == ramp.ascending;
    let sign = |positive: bool| if positive { 1.0 } else { -1.0 };
    let (rise, length) = (
        units.z(top) - units.z(foot),
        f64::from(run) * units.block_size,
    );
    // A local direction (along u, along v, up) to the grid's.
    let to_grid = |[a, b, c]: [f64; 3]| {
        let a = a * sign(ramp.ascending);
        if ramp.along_y { [b, a, c] } else { [a, b, c] }
    };
    let normal = |facing: Facing| match facing {
        Facing::Bottom => Normal::NegZ,
        Facing::Plane => Normal::tilted(to_grid([-rise, 0.0, length])),
        axis => {
            let v = to_grid(match axis {
                Facing::Foot => [-1.0, 0.0, 0.0],
                Facing::Head => [1.0, 0.0, 0.0],
                Facing::Right => [0.0, -1.0, 0.0],
                _ => [0.0, 1.0, 0.0],
            });
            match v {
                [x, _, _] if x > 0.0 => Normal::PosX,
                [x, _, _] if x < 0.0 => Normal::NegX,
                [_, y, _] if y > 0.0 => Normal::PosY,
                _ => Normal::NegY,
            }
        }
    };
    let points = local.into_iter().map(place).collect();
    let (triangles, normals) = faces
        .into_iter()
        .map(|([a, b, c], facing)| {
            let t = if mirrored { [a, c, b] } else { [a, b, c] };
            (t, normal(facing))
        })
        .unzip();
    Some((points, triangles, normals))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::LatticeVolume;
    use crate::mesh::invariants::lattice_faults;

    #[test]
    fn every_wedge_is_closed_with_its_volume_and_outward_normals() {
        for base in [0.0, 0.05] {
            let units = MeshUnits {
                block_size: 0.1,
                step_height: 0.05,
                base,
            };
            for (along_y, ascending) in [(false, true), (false, false), (true, true), (true, false)]
            {
                let ramp = Ramp {
                    cells: [2, 3, 6, 4],
                    along_y,
                    ascending,
                    rise: 4,
                };
                let (points, triangles, normals) = wedge(&ramp, units).unwrap();
                let lattice: Vec<[i128; 3]> =
                    points.iter().map(|&p| units.lattice_point(p)).collect();
                let positions: Vec<[f64; 3]> = lattice.iter().map(|&p| units.position(p)).collect();
                assert_eq!(lattice_faults(&lattice, &positions, &triangles), []);
                // Cells 5 × 2: a slab under all, half the rise on average.
                let (run, width) = if along_y { (2u64, 5u64) } else { (5, 2) };
                let cells = run * width;
                let slab = u64::from(base > 0.0);
                let expected = LatticeVolume::of_solid(cells * slab, cells * 4 / 2);
                assert!(
                    LatticeVolume::of(&points, &triangles).same_as(expected, units),
                    "{along_y} {ascending} {base}"
                );
                // Each normal points as its triangle's corners say.
                for (t, n) in triangles.iter().zip(&normals) {
                    let [p, q, r] = t.map(|i| positions[i as usize]);
                    let (a, b) = (
                        [q[0] - p[0], q[1] - p[1], q[2] - p[2]],
                        [r[0] - p[0], r[1] - p[1], r[2] - p[2]],
                    );
                    let cross = [
                        a[1] * b[2] - a[2] * b[1],
                        a[2] * b[0] - a[0] * b[2],
                        a[0] * b[1] - a[1] * b[0],
                    ];
                    let v = n.vector();
                    let length = cross.iter().map(|c| c * c).sum::<f64>().sqrt();
                    let cos: f64 = (0..3).map(|i| cross[i] * f64::from(v[i])).sum::<f64>() / length;
                    assert!(
                        cos > 0.9999,
                        "{along_y} {ascending}: {n:?} against {cross:?}"
                    );
                }
            }
        }
    }
}
