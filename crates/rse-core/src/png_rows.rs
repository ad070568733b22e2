//! PNG bytes of an RGB image given row by row, exactly as `png`'s encoder
//! writes them at `Compression::Fast` (adaptive row filters, `fdeflate`),
//! without the whole image in memory and without filtering a row that
//! repeats the one above it again.
//!
//! A preview is blocks of one colour: of a 510-pixel-high preview's rows,
//! 450 repeat the row above. `png` takes the whole image as one slice (780
//! KB drawn for every world) and runs its filters on every row; the PNG was
//! a fifth of a batch's time. Here a repeated row is known without looking:
//! its filtered bytes are zeros, which the adaptive filter picks first
//! (filter Up, cost 0). Every other row goes through the same filters, costs
//! and choice as `png`'s (`png::filter::adaptive_filter`, the PNG
//! specification's filters), and the filtered rows through the same
//! `fdeflate` compressor into one IDAT chunk: the bytes are `png`'s, which
//! the tests check against `png` itself on previews and random images.

use std::io::{self, Cursor};

use png::EncodingError;

/// Bytes per pixel: 8-bit RGB.
const BPP: usize = 3;

/// PNG filter types (PNG specification, 9.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
enum RowFilter {
    Sub = 1,
    Up = 2,
    Avg = 3,
    Paeth = 4,
}

/// The PNG of a `width`×`height` RGB image whose rows `rows` gives, in
/// order, to the function it is passed. `rows` may be called twice (for a
/// stored image, when compression would make it larger, as `png` does).
pub(crate) fn encode(
    width: u32,
    height: u32,
    rows: impl Fn(&mut dyn FnMut(&[u8]) -> io::Result<()>) -> io::Result<()>,
) -> Result<Vec<u8>, EncodingError> {
    let row_bytes = width as usize * BPP;
    let mut compressor = fdeflate::Compressor::new(Cursor::new(Vec::new()))?;
    let mut previous = vec![0; row_bytes];
    // The row being filtered, after its filter type byte.
    let mut filtered = vec![0; row_bytes + 1];
    // A row that repeats the one above: filter Up, all zeros.
    let mut repeated = vec![0; row_bytes + 1];
    repeated[0] = RowFilter::Up as u8;
    let mut count = 0u64;
    rows(&mut |row: &[u8]| {
        if row.len() != row_bytes {
            return Err(bad_size(format!(
                "a row of {} bytes in an image {width} pixels wide ({row_bytes} bytes)",
                row.len()
            )));
        }
        count += 1;
        if row == previous.as_slice() {
            return compressor.write_data(&repeated);
        }
        filtered[0] = adaptive_filter(&previous, row, &mut filtered[1..]) as u8;
        previous.copy_from_slice(row);
        compressor.write_data(&filtered)
    })?;
    if count != u64::from(height) {
        return Err(bad_size(format!("{count} rows in an image {height} pixels high")).into());
    }
    let mut zlib = compressor.finish()?.into_inner();
    let raw = (row_bytes + 1) * height as usize;
    if zlib.len() > fdeflate::StoredOnlyCompressor::<()>::compressed_size(raw) {
        let mut stored = fdeflate::StoredOnlyCompressor::new(Cursor::new(Vec::new()))?;
        rows(&mut |row: &[u8]| {
            stored.write_data(&[0])?;
            stored.write_data(row)
        })?;
        zlib = stored.finish()?.into_inner();
    }

    let mut bytes = Vec::with_capacity(zlib.len() + 64);
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header()?;
    // `png` splits its IDAT data at this length too.
    for chunk in zlib.chunks((u32::MAX >> 1) as usize) {
        writer.write_chunk(png::chunk::IDAT, chunk)?;
    }
    writer.finish()?;
    Ok(bytes)
}

/// An image whose rows do not match its size: refused, as `png` refuses
/// a buffer of the wrong size.
fn bad_size(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// Filters `current` (the row under `previous`) into `out` with the filter
/// `png`'s adaptive choice takes: Up, Sub, Avg, Paeth in turn, the lowest
/// sum of the bytes as signed magnitudes, a later filter winning a tie, the
/// first of cost 0 at once.
fn adaptive_filter(previous: &[u8], current: &[u8], out: &mut [u8]) -> RowFilter {
    let mut best = (u64::MAX, RowFilter::Up);
    for filter in [
        RowFilter::Up,
        RowFilter::Sub,
        RowFilter::Avg,
        RowFilter::Paeth,
    ] {
        apply(filter, previous, current, out);
        let cost: u64 = out
            .chunks(256)
            .map(|chunk| {
                // Sums of at most 256 * 128 fit a u32, which vectorizes.
                chunk
                    .iter()
                    .map(|&b| u32::from((b as i8).unsigned_abs()))
                    .sum::<u32>()
            })
            .map(u64::from)
            .sum();
        if cost <= best.0 {
            best = (cost, filter);
            if cost == 0 {
                return filter;
            }
        }
    }
    if best.1 != RowFilter::Paeth {
        apply(best.1, previous, current, out);
    }
    best.1
}

/// `filter` of `current` under `previous` into `out` (PNG specification,
/// 9.2; bytes left of the row and above the first row are zero). Written
/// as zipped slices, which the compiler turns into vector code: a
/// byte-by-byte loop made the filters slower than all of `png`.
fn apply(filter: RowFilter, previous: &[u8], current: &[u8], out: &mut [u8]) {
    let n = current.len();
    let (first, rest) = out.split_at_mut(BPP.min(n));
    let (left, up_left) = (&current[..n - first.len()], &previous[..n - first.len()]);
    let (cur, up) = (&current[first.len()..], &previous[first.len()..]);
    match filter {
        RowFilter::Up => {
            for ((o, &c), &u) in out.iter_mut().zip(current).zip(previous) {
                *o = c.wrapping_sub(u);
            }
        }
        RowFilter::Sub => {
            first.copy_from_slice(&current[..first.len()]);
            for ((o, &c), &l) in rest.iter_mut().zip(cur).zip(left) {
                *o = c.wrapping_sub(l);
            }
        }
        RowFilter::Avg => {
            for ((o, &c), &u) in first.iter_mut().zip(current).zip(previous) {
                *o = c.wrapping_sub(u / 2);
            }
            for (((o, &c), &l), &u) in rest.iter_mut().zip(cur).zip(left).zip(up) {
                // The floor of (l + u) / 2 without overflowing a byte.
                *o = c.wrapping_sub((l & u) + ((l ^ u) >> 1));
            }
        }
        RowFilter::Paeth => {
            for ((o, &c), &u) in first.iter_mut().zip(current).zip(previous) {
                *o = c.wrapping_sub(paeth(0, u, 0));
            }
            for ((((o, &c), &l), &u), &ul) in
                rest.iter_mut().zip(cur).zip(left).zip(up).zip(up_left)
            {
                *o = c.wrapping_sub(paeth(l, u, ul));
            }
        }
    }
}

/// The Paeth predictor of `a` (left), `b` (above), `c` (above left).
#[inline]
fn paeth(a: u8, b: u8, c: u8) -> u8 {
    let (a16, b16, c16) = (i16::from(a), i16::from(b), i16::from(c));
    let pa = (b16 - c16).abs();
    let pb = (a16 - c16).abs();
    let pc = (a16 + b16 - 2 * c16).abs();
    let b_or_c = if pb <= pc { b } else { c };
    if pa <= pb && pa <= pc { a } else { b_or_c }
}

/// The PNG `png`'s own encoder writes of an RGB image at
/// `Compression::Fast`: what [`encode`] must equal.
#[cfg(test)]
pub(crate) fn png_crate(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_compression(png::Compression::Fast);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(rgb).unwrap();
    writer.finish().unwrap();
    bytes
}

#[cfg(test)]
mod tests {
    use rand_chacha::ChaCha8Rng;
    use rand_chacha::rand_core::{Rng, SeedableRng};

    use super::*;

    fn ours(width: u32, height: u32, rgb: &[u8]) -> Vec<u8> {
        encode(width, height, |emit| {
            rgb.chunks(width as usize * BPP).try_for_each(&mut *emit)
        })
        .unwrap()
    }

    #[test]
    fn random_images_are_png_crate_bytes() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for case in 0..300 {
            let width = 1 + rng.next_u32() % 40;
            let height = 1 + rng.next_u32() % 30;
            let row_bytes = width as usize * BPP;
            // Rows that repeat, rows of few values (flat colours, small
            // steps), and noise (stored when it does not compress).
            let levels = [2, 4, 256][case % 3];
            let mut rgb: Vec<u8> = Vec::new();
            for y in 0..height as usize {
                if y > 0 && rng.next_u32() % 3 == 0 {
                    rgb.extend_from_within((y - 1) * row_bytes..y * row_bytes);
                } else {
                    rgb.extend((0..row_bytes).map(|_| ((rng.next_u32() % levels) * 37) as u8));
                }
            }
            assert_eq!(
                ours(width, height, &rgb),
                png_crate(width, height, &rgb),
                "case {case}: {width}x{height}, {levels} levels"
            );
        }
    }

    #[test]
    fn rows_that_do_not_match_the_size_are_refused() {
        let rgb = [7u8; 4 * 3 * 5];
        for (width, height) in [(4, 4), (4, 6), (3, 5)] {
            let result = encode(width, height, |emit| {
                rgb.chunks(12).try_for_each(&mut *emit)
            });
            assert!(result.is_err(), "{width}x{height}");
        }
        assert!(encode(4, 5, |emit| rgb.chunks(12).try_for_each(&mut *emit)).is_ok());
    }

    #[test]
    fn every_filter_is_chosen_somewhere() {
        // The choice covers Up, Sub, Avg and Paeth on these rows, so a
        // filter computed wrongly would change bytes the test above sees.
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut seen = [false; 5];
        for _ in 0..2000 {
            let previous: Vec<u8> = (0..12).map(|_| (rng.next_u32() % 4) as u8 * 60).collect();
            let current: Vec<u8> = (0..12).map(|_| (rng.next_u32() % 4) as u8 * 60).collect();
            let mut out = vec![0; 12];
            seen[adaptive_filter(&previous, &current, &mut out) as usize] = true;
        }
        assert_eq!(seen, [false, true, true, true, true]);
    }
}
