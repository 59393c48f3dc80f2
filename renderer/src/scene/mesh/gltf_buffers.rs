//! glTF URIs and buffers: `data:` URIs (base64), percent-encoded relative paths, and the
//! buffers a file's primitives and images read, a `.glb`'s BIN chunk among them. Shared by the
//! geometry reader (`gltf.rs`) and the material reader (`gltf_materials.rs`).

use super::MeshError;
use ::gltf::Document;
use ::gltf::buffer::Source;
use std::borrow::Cow;
use std::path::Path;

/// The data of every buffer marked in `needed` (others stay empty), each at least its declared
/// `byteLength` long; `bin` is a `.glb`'s BIN chunk (buffer 0).
pub(super) fn load_buffers<'a>(
    file: &Path,
    doc: &Document,
    needed: &[bool],
    glb: bool,
    bin: Option<&'a [u8]>,
) -> Result<Vec<Cow<'a, [u8]>>, MeshError> {
    let folder = file.parent().unwrap_or(Path::new(""));
    let mut out = Vec::with_capacity(needed.len());
    for buffer in doc.buffers() {
        let index = buffer.index();
        let at = |m: String| MeshError::at(file, &format!("buffer {index}"), m);
        if !needed[index] {
            out.push(Cow::Borrowed(&[][..]));
            continue;
        }
        let (data, what): (Cow<[u8]>, String) = match buffer.source() {
            Source::Bin => match bin {
                Some(bin) if index == 0 => (Cow::Borrowed(bin), "the BIN chunk".into()),
                None if index == 0 && glb => {
                    return Err(at("has no uri and the .glb has no BIN chunk".into()));
                }
                _ => {
                    return Err(at(
                        "has no uri (only buffer 0 of a .glb may, for its BIN chunk)".into(),
                    ));
                }
            },
            Source::Uri(uri) => {
                let (data, what) = read_uri(folder, uri).map_err(at)?;
                (Cow::Owned(data), what)
            }
        };
        if data.len() < buffer.length() {
            return Err(at(format!(
                "{what} has {} bytes, fewer than its byteLength {}",
                data.len(),
                buffer.length()
            )));
        }
        out.push(data);
    }
    Ok(out)
}

/// The bytes a buffer's or an image's `uri` names, and how to name it in messages (`its data
/// URI`, `'wood.png'`): a base64 `data:` URI, or a percent-encoded path relative to `folder`.
pub(super) fn read_uri(folder: &Path, uri: &str) -> Result<(Vec<u8>, String), String> {
    if uri.starts_with("data:") {
        return Ok((decode_data_uri(uri)?, "its data URI".into()));
    }
    let name = relative_path(uri)?;
    let data =
        std::fs::read(folder.join(&name)).map_err(|e| format!("cannot read '{name}': {e}"))?;
    Ok((data, format!("'{name}'")))
}

/// The relative path a `uri` (not a data URI) names, percent-decoded; an error for another
/// scheme.
pub(super) fn relative_path(uri: &str) -> Result<String, String> {
    let name = percent_decode(uri).map_err(|m| format!("uri '{uri}': {m}"))?;
    if let Some(scheme) = uri_scheme(&name) {
        return Err(format!(
            "uri '{uri}': unsupported scheme '{scheme}' (lumis reads relative paths and data: \
             URIs)"
        ));
    }
    Ok(name)
}

/// The scheme of an absolute URI (`http`, `file`), if `uri` has one; a one-letter "scheme" is a
/// Windows drive and is left to the file system.
fn uri_scheme(uri: &str) -> Option<&str> {
    let colon = uri.find(':')?;
    let scheme = &uri[..colon];
    let valid = scheme.len() > 1
        && scheme.starts_with(|c: char| c.is_ascii_alphabetic())
        && scheme
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c));
    valid.then_some(scheme)
}

/// URIs in glTF are percent-encoded (`my%20mesh.bin`).
fn percent_decode(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%'
            && let (Some(h), Some(l)) = (
                bytes.get(i + 1).and_then(|&b| hex(b)),
                bytes.get(i + 2).and_then(|&b| hex(b)),
            )
        {
            out.push((h * 16 + l) as u8);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "not UTF-8 once percent-decoded".to_string())
}

/// The bytes of a `data:[<media type>];base64,<data>` URI (glTF writers use
/// `application/octet-stream` or `application/gltf-buffer`; any media type is accepted).
fn decode_data_uri(uri: &str) -> Result<Vec<u8>, String> {
    let comma = uri
        .find(',')
        .ok_or_else(|| "data URI without a ','".to_string())?;
    if !uri[..comma].ends_with(";base64") {
        return Err(format!(
            "data URI '{}…' is not base64 (lumis reads base64 data URIs)",
            &uri[..comma]
        ));
    }
    decode_base64(&uri[comma + 1..]).map_err(|m| format!("data URI: {m}"))
}

/// Standard base64 (RFC 4648 alphabet, padding optional). A dozen lines here instead of a
/// dependency that nothing else in the workspace pulls in.
pub(super) fn decode_base64(text: &str) -> Result<Vec<u8>, String> {
    let text = text.trim_end_matches('=');
    let mut out = Vec::with_capacity(text.len() / 4 * 3 + 2);
    let (mut acc, mut bits) = (0u32, 0u32);
    for (i, c) in text.bytes().enumerate() {
        let v = match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => return Err(format!("invalid base64 character {:?} at {i}", c as char)),
        };
        acc = (acc << 6) | v as u32;
        bits += 6;
        if bits >= 8 {
            bits -= 8;
            out.push((acc >> bits) as u8);
            acc &= (1 << bits) - 1;
        }
    }
    if text.len() % 4 == 1 {
        return Err("truncated base64 (one character too many)".to_string());
    }
    Ok(out)
}
