//! Single depth images: binary 16-bit PGM (P5) and 16-bit greyscale PNG.
//!
//! Headers are checked before any buffer is sized from them: a header claiming a
//! 200000×200000 image fails at once, without allocating.

use std::io::Read;
use std::path::Path;

use crate::{DepthFrame, DriverError, MAX_HEIGHT, MAX_WIDTH};

/// Byte order of the 16-bit samples in a PGM body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ByteOrder {
    /// Most significant byte first, as the Netpbm specification says.
    BigEndian,
    /// Least significant byte first, as libfreenect's `record` tool writes raw frames.
    LittleEndian,
}

/// A parsed PGM header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PgmHeader {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Maximum sample value.
    pub maxval: u32,
    /// Offset of the first sample byte.
    pub data_offset: usize,
}

/// Parse a binary PGM (`P5`) header: magic, width, height, maxval, with `#` comments,
/// then exactly one whitespace byte before the samples.
pub fn parse_pgm_header(bytes: &[u8], path: &Path) -> Result<PgmHeader, DriverError> {
    if bytes.len() < 2 || &bytes[..2] != b"P5" {
        let what = if bytes.len() >= 2 && bytes[0] == b'P' {
            format!(
                "not a binary greyscale PGM: magic {:?}, expected \"P5\"",
                String::from_utf8_lossy(&bytes[..2])
            )
        } else {
            "not a PGM file: missing \"P5\" magic".to_string()
        };
        return Err(DriverError::malformed(path, what));
    }
    let mut pos = 2;
    let mut fields = [0u64; 3];
    for (i, name) in ["width", "height", "maxval"].iter().enumerate() {
        // Whitespace and comments before each field; at least one whitespace.
        let start = pos;
        loop {
            match bytes.get(pos) {
                Some(b'#') => {
                    while let Some(&c) = bytes.get(pos) {
                        pos += 1;
                        if c == b'\n' || c == b'\r' {
                            break;
                        }
                    }
                }
                Some(c) if c.is_ascii_whitespace() => pos += 1,
                _ => break,
            }
        }
        if pos >= bytes.len() {
            return Err(DriverError::malformed(
                path,
                format!("PGM header truncated before {name}"),
            ));
        }
        if pos == start {
            return Err(DriverError::malformed(
                path,
                format!("PGM header: expected whitespace before {name}"),
            ));
        }
        let digits_start = pos;
        let mut value: u64 = 0;
        while let Some(&c) = bytes.get(pos) {
            if !c.is_ascii_digit() {
                break;
            }
            value = value.saturating_mul(10).saturating_add(u64::from(c - b'0'));
            pos += 1;
        }
        if pos == digits_start {
            return Err(DriverError::malformed(
                path,
                if pos >= bytes.len() {
                    format!("PGM header truncated before {name}")
                } else {
                    format!("PGM header: {name} is not a number")
                },
            ));
        }
        fields[i] = value;
    }
    match bytes.get(pos) {
        Some(c) if c.is_ascii_whitespace() => pos += 1,
        Some(_) => {
            return Err(DriverError::malformed(
                path,
                "PGM header: expected one whitespace byte after maxval",
            ))
        }
        None => {
            return Err(DriverError::malformed(
                path,
                "PGM truncated after the header",
            ))
        }
    }
    let [width, height, maxval] = fields;
    check_dimensions(width, height, path)?;
    if maxval == 0 || maxval > 65535 {
        return Err(DriverError::malformed(
            path,
            format!("PGM maxval {maxval} is outside 1..=65535"),
        ));
    }
    Ok(PgmHeader {
        width: width as usize,
        height: height as usize,
        maxval: maxval as u32,
        data_offset: pos,
    })
}

fn check_dimensions(width: u64, height: u64, path: &Path) -> Result<(), DriverError> {
    if width == 0 || height == 0 {
        return Err(DriverError::malformed(
            path,
            format!("image has no pixels ({width}×{height})"),
        ));
    }
    if width > MAX_WIDTH as u64 || height > MAX_HEIGHT as u64 {
        return Err(DriverError::malformed(
            path,
            format!("absurd image size {width}×{height} (at most {MAX_WIDTH}×{MAX_HEIGHT})"),
        ));
    }
    Ok(())
}

/// Decode a 16-bit depth PGM held in `bytes` into `frame` (maxval must be 65535).
pub fn decode_pgm_depth(
    bytes: &[u8],
    order: ByteOrder,
    path: &Path,
    frame: &mut DepthFrame,
) -> Result<(), DriverError> {
    let header = parse_pgm_header(bytes, path)?;
    if header.maxval != 65535 {
        return Err(DriverError::malformed(
            path,
            format!(
                "depth PGM must be 16-bit with maxval 65535, found maxval {}",
                header.maxval
            ),
        ));
    }
    let need = header.width * header.height * 2;
    let body = &bytes[header.data_offset..];
    if body.len() < need {
        return Err(DriverError::malformed(
            path,
            format!(
                "truncated: {}×{} 16-bit samples need {need} bytes, found {}",
                header.width,
                header.height,
                body.len()
            ),
        ));
    }
    if body.len() > need {
        return Err(DriverError::malformed(
            path,
            format!(
                "{} unexpected bytes after the {}×{} samples",
                body.len() - need,
                header.width,
                header.height
            ),
        ));
    }
    let pixels = frame.reshape(header.width, header.height);
    for (dst, src) in pixels.iter_mut().zip(body.chunks_exact(2)) {
        let pair = [src[0], src[1]];
        *dst = match order {
            ByteOrder::BigEndian => u16::from_be_bytes(pair),
            ByteOrder::LittleEndian => u16::from_le_bytes(pair),
        };
    }
    Ok(())
}

/// Decode a 16-bit greyscale PNG held in `bytes` into `frame`.
pub fn decode_png_depth(
    bytes: &[u8],
    path: &Path,
    frame: &mut DepthFrame,
) -> Result<(), DriverError> {
    let mut decoder = png::Decoder::new_with_limits(
        bytes,
        png::Limits {
            bytes: MAX_WIDTH * MAX_HEIGHT * 2,
        },
    );
    decoder.set_transformations(png::Transformations::IDENTITY);
    let bad = |e: png::DecodingError| DriverError::malformed(path, format!("PNG: {e}"));
    let mut reader = decoder.read_info().map_err(bad)?;
    let info = reader.info();
    check_dimensions(u64::from(info.width), u64::from(info.height), path)?;
    if info.color_type != png::ColorType::Grayscale || info.bit_depth != png::BitDepth::Sixteen {
        return Err(DriverError::malformed(
            path,
            format!(
                "depth PNG must be 16-bit greyscale, found {:?} {:?}-bit",
                info.color_type, info.bit_depth as u8
            ),
        ));
    }
    let (width, height) = (info.width as usize, info.height as usize);
    let mut raw = vec![0u8; width * height * 2];
    reader.next_frame(&mut raw).map_err(bad)?;
    let pixels = frame.reshape(width, height);
    for (dst, src) in pixels.iter_mut().zip(raw.chunks_exact(2)) {
        *dst = u16::from_be_bytes([src[0], src[1]]);
    }
    Ok(())
}

/// Encode a depth frame as a 16-bit greyscale PNG (fixtures, recordings).
pub fn encode_png_depth(frame: &DepthFrame) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, frame.width() as u32, frame.height() as u32);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Sixteen);
        encoder.set_compression(png::Compression::Best);
        let mut writer = encoder
            .write_header()
            .expect("writing a PNG header into memory cannot fail");
        let mut data = Vec::with_capacity(frame.pixels().len() * 2);
        for p in frame.pixels() {
            data.extend_from_slice(&p.to_be_bytes());
        }
        writer
            .write_image_data(&data)
            .expect("writing PNG data into memory cannot fail");
    }
    out
}

/// Encode a depth frame as a binary big-endian 16-bit PGM.
pub fn encode_pgm_depth(frame: &DepthFrame) -> Vec<u8> {
    let mut out = format!("P5\n{} {}\n65535\n", frame.width(), frame.height()).into_bytes();
    out.reserve(frame.pixels().len() * 2);
    for p in frame.pixels() {
        out.extend_from_slice(&p.to_be_bytes());
    }
    out
}

/// The kinds of image file this module reads, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageKind {
    /// `.pgm`
    Pgm,
    /// `.png`
    Png,
}

impl ImageKind {
    /// The kind for a path's extension (case-insensitive), if it is one we read.
    pub fn of(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "pgm" => Some(ImageKind::Pgm),
            "png" => Some(ImageKind::Png),
            _ => None,
        }
    }
}

/// Read a file into `scratch` (reusing its capacity).
pub fn read_file_into(path: &Path, scratch: &mut Vec<u8>) -> Result<(), DriverError> {
    scratch.clear();
    let mut file = std::fs::File::open(path).map_err(|e| DriverError::io(path, e))?;
    file.read_to_end(scratch)
        .map_err(|e| DriverError::io(path, e))?;
    Ok(())
}

/// Read one depth image file (PGM or PNG by extension) into `frame`.
pub fn read_depth_image(
    path: &Path,
    scratch: &mut Vec<u8>,
    frame: &mut DepthFrame,
) -> Result<(), DriverError> {
    let kind = ImageKind::of(path).ok_or_else(|| {
        DriverError::malformed(path, "unknown image type (expected .pgm or .png)")
    })?;
    read_file_into(path, scratch)?;
    match kind {
        ImageKind::Pgm => decode_pgm_depth(scratch, ByteOrder::BigEndian, path, frame),
        ImageKind::Png => decode_png_depth(scratch, path, frame),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> &'static Path {
        Path::new("t.pgm")
    }

    fn pgm(header: &str, body: &[u8]) -> Vec<u8> {
        let mut v = header.as_bytes().to_vec();
        v.extend_from_slice(body);
        v
    }

    #[test]
    fn reads_big_endian_pgm_with_comments() {
        let bytes = pgm(
            "P5\n# made by hand\n2 1\n65535\n",
            &[0x01, 0x02, 0xff, 0x00],
        );
        let mut f = DepthFrame::default();
        decode_pgm_depth(&bytes, ByteOrder::BigEndian, p(), &mut f).unwrap();
        assert_eq!((f.width(), f.height()), (2, 1));
        assert_eq!(f.pixels(), &[0x0102, 0xff00]);
    }

    #[test]
    fn reads_little_endian_samples() {
        let bytes = pgm("P5 2 1 65535\n", &[0x01, 0x02, 0xff, 0x00]);
        let mut f = DepthFrame::default();
        decode_pgm_depth(&bytes, ByteOrder::LittleEndian, p(), &mut f).unwrap();
        assert_eq!(f.pixels(), &[0x0201, 0x00ff]);
    }

    fn err(bytes: &[u8]) -> String {
        let mut f = DepthFrame::default();
        decode_pgm_depth(bytes, ByteOrder::BigEndian, p(), &mut f)
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn rejects_malformed_pgm_with_reason_and_file() {
        assert!(err(b"P2 1 1 65535\n0").contains("magic"));
        assert!(err(b"GIF89a").contains("P5"));
        assert!(err(b"P5 2 2 255\n\0\0\0\0").contains("maxval 255"));
        assert!(err(b"P5 2 2 65535\n\0\0").contains("truncated"));
        assert!(err(b"P5 1 1 65535\n\0\0\0").contains("unexpected bytes"));
        assert!(err(b"P5 200000 200000 65535\n").contains("absurd"));
        assert!(err(b"P5 0 5 65535\n").contains("no pixels"));
        assert!(err(b"P5 2").contains("truncated"));
        assert!(err(b"P5 x 2 65535\n").contains("not a number"));
        assert!(err(b"P5 1 1 99999999\n").contains("maxval"));
        assert!(err(b"P5 1 1 65535\n").starts_with("t.pgm: "));
    }

    #[test]
    fn absurd_header_fails_without_allocating_the_claimed_size() {
        // 18446744073709551615 saturates; must be an error, not an attempt to allocate.
        let e = err(b"P5 18446744073709551615 18446744073709551615 65535\n");
        assert!(e.contains("absurd"), "{e}");
    }

    #[test]
    fn png_round_trip_and_rejections() {
        let frame = DepthFrame::from_pixels(3, 2, vec![0, 1, 500, 65535, 1234, 4000]);
        let bytes = encode_png_depth(&frame);
        let mut back = DepthFrame::default();
        decode_png_depth(&bytes, Path::new("a.png"), &mut back).unwrap();
        assert_eq!(back.pixels(), frame.pixels());
        assert_eq!((back.width(), back.height()), (3, 2));

        let e = decode_png_depth(&bytes[..bytes.len() / 2], Path::new("a.png"), &mut back)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("a.png: PNG"), "{e}");

        // An 8-bit PNG is not depth.
        let mut out = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut out, 1, 1);
            enc.set_color(png::ColorType::Grayscale);
            enc.set_depth(png::BitDepth::Eight);
            enc.write_header().unwrap().write_image_data(&[7]).unwrap();
        }
        let e = decode_png_depth(&out, Path::new("b.png"), &mut back)
            .unwrap_err()
            .to_string();
        assert!(e.contains("16-bit greyscale"), "{e}");
    }

    #[test]
    fn pgm_round_trip() {
        let frame = DepthFrame::from_pixels(2, 2, vec![1, 2, 3, 65535]);
        let bytes = encode_pgm_depth(&frame);
        let mut back = DepthFrame::default();
        decode_pgm_depth(&bytes, ByteOrder::BigEndian, p(), &mut back).unwrap();
        assert_eq!(back.pixels(), frame.pixels());
    }
}
