//! The difficulty contract on every sample: D = 1 is `generate`, D = 0 is
//! flat but for the frames, and every cell is `floor(D·h + 0.5)` of its
//! D = 1 height, so the layout is kept and heights grow with D.

use rse_core::{Difficulty, Scheme, generate, generate_at};

use crate::util::sample_paths;

const LEVELS: [f64; 6] = [0.0, 0.2, 0.35, 0.5, 0.8, 1.0];

#[test]
fn every_cell_is_its_full_height_scaled() {
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let grid = scheme.grid();
        for index in 0..3 {
            let full = generate(&scheme, 7, index);
            let mut previous: Option<Vec<u16>> = None;
            for d in LEVELS.map(|d| Difficulty::new(d).unwrap()) {
                let terrain = generate_at(&scheme, 7, index, d);
                assert_eq!(terrain.drawn(), full.drawn(), "{}", path.display());
                assert_eq!(terrain.difficulty(), d);
                for y in 0..grid.ny {
                    for x in 0..grid.nx {
                        let want = if grid.is_frame(x, y) {
                            1
                        } else {
                            d.scale(full.heightmap().get(x, y))
                        };
                        assert_eq!(
                            terrain.heightmap().get(x, y),
                            want,
                            "{} D {d}",
                            path.display()
                        );
                    }
                }
                let cells = terrain.heightmap().cells().to_vec();
                if let Some(easier) = &previous {
                    assert!(easier.iter().zip(&cells).all(|(a, b)| a <= b));
                }
                previous = Some(cells);
            }
        }
    }
}

#[test]
fn full_difficulty_is_generate_and_zero_is_flat() {
    for path in sample_paths() {
        let scheme = Scheme::load(&path).unwrap();
        let grid = scheme.grid();
        assert_eq!(
            generate_at(&scheme, 3, 1, Difficulty::FULL),
            generate(&scheme, 3, 1)
        );
        let flat = generate_at(&scheme, 3, 1, Difficulty::new(0.0).unwrap());
        for y in 0..grid.ny {
            for x in 0..grid.nx {
                let want = u16::from(grid.is_frame(x, y));
                assert_eq!(flat.heightmap().get(x, y), want, "{}", path.display());
            }
        }
    }
}
