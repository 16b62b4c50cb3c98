//! What SSH compression would send: one zlib stream across all frames, sync-flushed after each.

use std::io::Write;

use flate2::write::ZlibEncoder;
use flate2::Compression;

/// One deflate context; `frame` returns the compressed bytes one frame adds to the stream.
pub struct ZlibMeter {
    z: ZlibEncoder<Vec<u8>>,
}

impl Default for ZlibMeter {
    fn default() -> Self {
        Self::new()
    }
}

impl ZlibMeter {
    /// A fresh stream at zlib's default level (6, as OpenSSH uses).
    #[must_use]
    pub fn new() -> Self {
        Self {
            z: ZlibEncoder::new(Vec::new(), Compression::default()),
        }
    }

    /// Compresses one frame with a sync flush; the byte count it added.
    ///
    /// # Panics
    /// Never: compressing into a `Vec` cannot fail.
    pub fn frame(&mut self, bytes: &[u8]) -> usize {
        self.z.get_mut().clear();
        self.z.write_all(bytes).expect("in-memory");
        self.z.flush().expect("in-memory");
        self.z.get_ref().len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_frames_compress_to_almost_nothing() {
        let mut z = ZlibMeter::new();
        let mut x = 12345u32;
        let frame: Vec<u8> = (0..5000)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                x as u8
            })
            .collect();
        let first = z.frame(&frame);
        let again = z.frame(&frame);
        assert!(first > 1000 && again < 100, "{first} {again}");
    }
}
