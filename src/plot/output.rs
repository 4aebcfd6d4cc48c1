//! Writing the rendered image: PNG encoding and an atomic write (temporary file in the same
//! directory, then rename), so that a failed plot never leaves a partial file behind.

use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use super::raster::Canvas;
use crate::error::{LtiError, Result};

fn io_err(path: &Path, e: impl std::fmt::Display) -> LtiError {
    LtiError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// Encodes the canvas as an 8-bit RGB PNG.
pub(crate) fn encode_png(
    canvas: &Canvas,
    out: impl Write,
) -> std::result::Result<(), png::EncodingError> {
    let mut enc = png::Encoder::new(out, canvas.w, canvas.h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    // Plots are mostly flat colour: fast deflate with the Paeth-free "Sub" filter is ~5× faster
    // than the default level and only slightly larger.
    enc.set_compression(png::Compression::Fast);
    enc.set_filter(png::FilterType::Sub);
    let mut writer = enc.write_header()?;
    writer.write_image_data(canvas.pixels())?;
    writer.finish()
}

/// The temporary sibling of `path`: `.name.png.tmp-<pid>-<n>` in the same directory.
fn temp_path(path: &Path) -> Result<PathBuf> {
    use std::sync::atomic::{AtomicU64, Ordering};
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| io_err(path, "not a file name"))?
        .to_string_lossy()
        .into_owned();
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let tmp = format!(".{name}.tmp-{}-{n}", std::process::id());
    Ok(match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.join(tmp),
        _ => PathBuf::from(tmp),
    })
}

/// Writes `bytes` to `path` atomically (a temporary sibling, then a rename): an error leaves
/// no file (the plant files of `c2d`/`d2c -o`; used by the command line only).
#[cfg(feature = "cli")]
pub(crate) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let tmp = temp_path(path)?;
    let result = (|| -> Result<()> {
        fs::write(&tmp, bytes).map_err(|e| io_err(path, e))?;
        fs::rename(&tmp, path).map_err(|e| io_err(path, e))
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}

/// Writes the canvas to `path` as PNG atomically.
pub(crate) fn write_png(canvas: &Canvas, path: &Path) -> Result<()> {
    let tmp = temp_path(path)?;
    let result = (|| -> Result<()> {
        let file = fs::File::create(&tmp).map_err(|e| io_err(path, e))?;
        let mut w = BufWriter::with_capacity(1 << 16, file);
        encode_png(canvas, &mut w).map_err(|e| io_err(path, e))?;
        let file = w.into_inner().map_err(|e| io_err(path, e.error()))?;
        drop(file);
        fs::rename(&tmp, path).map_err(|e| io_err(path, e))
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result
}
