//! glTF containers written byte by byte, for tests that build glTF files in memory (the reader's
//! own tests and the integration tests' mutations and scenes): a `.glb` from its JSON and BIN
//! chunks, and base64 for a `.gltf`'s `data:` URIs. Test code: only with the `testing` feature.

/// A `.glb` container (glTF 2.0 binary, version 2): the 12-byte header, the JSON chunk padded
/// with spaces and the optional BIN chunk padded with zeros to 4 bytes, as the spec requires.
pub fn glb(json: &str, bin: Option<&[u8]>) -> Vec<u8> {
    let mut j = json.as_bytes().to_vec();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut chunks = Vec::new();
    chunks.extend((j.len() as u32).to_le_bytes());
    chunks.extend(b"JSON");
    chunks.extend(&j);
    if let Some(bin) = bin {
        let mut b = bin.to_vec();
        while !b.len().is_multiple_of(4) {
            b.push(0);
        }
        chunks.extend((b.len() as u32).to_le_bytes());
        chunks.extend(b"BIN\0");
        chunks.extend(&b);
    }
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((12 + chunks.len() as u32).to_le_bytes());
    out.extend(chunks);
    out
}

/// Standard base64 (RFC 4648 alphabet, with `=` padding): the encoder twin of the reader's
/// `decode_base64`.
pub fn base64(bytes: &[u8]) -> String {
    const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for c in bytes.chunks(3) {
        let n = (c[0] as u32) << 16
            | (*c.get(1).unwrap_or(&0) as u32) << 8
            | *c.get(2).unwrap_or(&0) as u32;
        for k in 0..4 {
            if k <= c.len() {
                out.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_round_trips_through_the_reader() {
        for n in 0..10u8 {
            let bytes: Vec<u8> = (0..n)
                .map(|i| i.wrapping_mul(97).wrapping_add(13))
                .collect();
            let text = base64(&bytes);
            assert_eq!(text.len(), bytes.len().div_ceil(3) * 4);
            assert_eq!(super::super::buffers::decode_base64(&text).unwrap(), bytes);
        }
        assert_eq!(base64(b"Man"), "TWFu");
        assert_eq!(base64(b"Ma"), "TWE=");
    }

    #[test]
    fn glb_chunks_are_aligned_and_the_length_is_the_file_s() {
        let b = glb("{}", Some(&[1, 2, 3]));
        assert_eq!(&b[0..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes(b[8..12].try_into().unwrap()) as usize,
            b.len()
        );
        // JSON chunk: "{}" padded to 4, then the BIN chunk of 3 bytes padded to 4.
        assert_eq!(&b[12..20], &[4, 0, 0, 0, b'J', b'S', b'O', b'N']);
        assert_eq!(&b[20..24], b"{}  ");
        assert_eq!(&b[24..32], &[4, 0, 0, 0, b'B', b'I', b'N', 0]);
        assert_eq!(&b[32..36], &[1, 2, 3, 0]);
    }
}
