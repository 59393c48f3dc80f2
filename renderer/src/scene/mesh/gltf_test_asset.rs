//! glTF files for tests, built in memory: JSON plus one buffer of bytes, written to
//! `temp_dir()/lumis-gltf-test-<pid>/<test>` (removed when the test ends) as a `.gltf` with an
//! external or a `data:` buffer, or as a `.glb`. Shared by the geometry, material and model
//! tests.

pub(crate) use super::bytes::{base64, glb};
use serde_json::{Value, json};
use std::path::PathBuf;

pub(crate) const FLOAT: u32 = 5126;
pub(crate) const U8: u32 = 5121;
pub(crate) const U16: u32 = 5123;
pub(crate) const U32: u32 = 5125;

/// A per-test folder, removed on drop.
pub(crate) struct Dir(pub(crate) PathBuf);

impl Dir {
    pub(crate) fn new(test: &str) -> Dir {
        let dir = std::env::temp_dir()
            .join(format!("lumis-gltf-test-{}", std::process::id()))
            .join(test);
        let _ = std::fs::remove_dir_all(&dir);
        // Another test's drop may remove the (still empty) per-process folder between the two
        // steps of `create_dir_all`; once this folder is in it, it stays.
        let mut created = std::fs::create_dir_all(&dir);
        for _ in 0..100 {
            if created.is_ok() {
                break;
            }
            created = std::fs::create_dir_all(&dir);
        }
        created.unwrap();
        Dir(dir)
    }

    pub(crate) fn file(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for Dir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
        // The per-process folder goes with the last test (fails harmlessly while others run).
        if let Some(parent) = self.0.parent() {
            let _ = std::fs::remove_dir(parent);
        }
    }
}

/// A glTF asset under construction: one buffer (`bin`), its views and accessors, meshes, nodes.
/// Without explicit scenes, `json` makes one scene of all nodes that are no one's child.
#[derive(Default)]
pub(crate) struct Asset {
    pub(crate) bin: Vec<u8>,
    pub(crate) views: Vec<Value>,
    pub(crate) accessors: Vec<Value>,
    pub(crate) meshes: Vec<Value>,
    pub(crate) nodes: Vec<Value>,
    pub(crate) scenes: Option<Value>,
    pub(crate) scene: Option<usize>,
    /// Extra top-level members (`extensionsRequired`, more buffers, ...).
    pub(crate) root: serde_json::Map<String, Value>,
}

impl Asset {
    pub(crate) fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.views
            .push(json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()}));
        self.bin.extend_from_slice(bytes);
        self.views.len() - 1
    }

    pub(crate) fn accessor(&mut self, mut a: Value) -> usize {
        if a.get("byteOffset").is_none() && a.get("bufferView").is_some() {
            a["byteOffset"] = json!(0);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    pub(crate) fn vec3(&mut self, data: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for p in data {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let (lo, hi) = (lo.map(finite_or_zero), hi.map(finite_or_zero));
        self.accessor(
            json!({"bufferView": view, "componentType": FLOAT, "type": "VEC3",
            "count": data.len(), "min": lo, "max": hi}),
        )
    }

    pub(crate) fn vec2(&mut self, data: &[[f32; 2]]) -> usize {
        let bytes: Vec<u8> = data
            .iter()
            .flatten()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        let view = self.view(&bytes);
        self.accessor(
            json!({"bufferView": view, "componentType": FLOAT, "type": "VEC2",
            "count": data.len()}),
        )
    }

    pub(crate) fn indices(&mut self, indices: &[u32], component: u32) -> usize {
        let bytes: Vec<u8> = match component {
            U8 => indices.iter().map(|&i| i as u8).collect(),
            U16 => indices
                .iter()
                .flat_map(|&i| (i as u16).to_le_bytes())
                .collect(),
            _ => indices.iter().flat_map(|&i| i.to_le_bytes()).collect(),
        };
        let view = self.view(&bytes);
        self.accessor(
            json!({"bufferView": view, "componentType": component, "type": "SCALAR",
            "count": indices.len()}),
        )
    }

    pub(crate) fn mesh(&mut self, primitives: Vec<Value>) -> usize {
        self.meshes.push(json!({ "primitives": primitives }));
        self.meshes.len() - 1
    }

    pub(crate) fn node(&mut self, node: Value) -> usize {
        self.nodes.push(node);
        self.nodes.len() - 1
    }

    pub(crate) fn json(&self, uri: Option<String>) -> Value {
        let mut buffer = json!({"byteLength": self.bin.len()});
        if let Some(uri) = uri {
            buffer["uri"] = json!(uri);
        }
        let mut root = json!({
            "asset": {"version": "2.0"},
            "buffers": [buffer],
            "bufferViews": self.views,
            "accessors": self.accessors,
            "meshes": self.meshes,
            "nodes": self.nodes,
        });
        let scenes = self.scenes.clone().unwrap_or_else(|| {
            let children: Vec<u64> = self
                .nodes
                .iter()
                .flat_map(|n| n["children"].as_array().cloned().unwrap_or_default())
                .filter_map(|c| c.as_u64())
                .collect();
            let roots: Vec<usize> = (0..self.nodes.len())
                .filter(|i| !children.contains(&(*i as u64)))
                .collect();
            json!([{ "nodes": roots }])
        });
        root["scenes"] = scenes;
        if let Some(scene) = self.scene {
            root["scene"] = json!(scene);
        }
        for (k, v) in &self.root {
            root[k] = v.clone();
        }
        root
    }

    /// `name.gltf` with its buffer in `bin_name` beside it (`uri` as written in the JSON).
    pub(crate) fn write_external(
        &self,
        dir: &Dir,
        name: &str,
        bin_name: &str,
        uri: &str,
    ) -> PathBuf {
        std::fs::write(dir.file(bin_name), &self.bin).unwrap();
        let path = dir.file(name);
        std::fs::write(&path, self.json(Some(uri.to_string())).to_string()).unwrap();
        path
    }

    pub(crate) fn write_embedded(&self, dir: &Dir, name: &str, media: &str) -> PathBuf {
        let uri = format!("data:{media};base64,{}", base64(&self.bin));
        let path = dir.file(name);
        std::fs::write(&path, self.json(Some(uri)).to_string()).unwrap();
        path
    }

    pub(crate) fn write_glb(&self, dir: &Dir, name: &str) -> PathBuf {
        let path = dir.file(name);
        std::fs::write(&path, glb(&self.json(None).to_string(), Some(&self.bin))).unwrap();
        path
    }
}

pub(crate) fn finite_or_zero(f: f32) -> f32 {
    if f.is_finite() { f } else { 0.0 }
}

pub(crate) fn primitive(
    pos: usize,
    normal: Option<usize>,
    uv: Option<usize>,
    indices: Option<usize>,
) -> Value {
    let mut attributes = json!({ "POSITION": pos });
    if let Some(n) = normal {
        attributes["NORMAL"] = json!(n);
    }
    if let Some(t) = uv {
        attributes["TEXCOORD_0"] = json!(t);
    }
    let mut p = json!({ "attributes": attributes });
    if let Some(i) = indices {
        p["indices"] = json!(i);
    }
    p
}

pub(crate) const QUAD: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];
pub(crate) const QUAD_UV: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
pub(crate) const QUAD_TRIS: [u32; 6] = [0, 1, 2, 0, 2, 3];

/// A unit quad in z = 0 facing +z, with normals, UVs and `component` indices, on one node.
pub(crate) fn quad(component: u32) -> Asset {
    let mut a = Asset::default();
    let pos = a.vec3(&QUAD);
    let nrm = a.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv = a.vec2(&QUAD_UV);
    let idx = a.indices(&QUAD_TRIS, component);
    let mesh = a.mesh(vec![primitive(pos, Some(nrm), Some(uv), Some(idx))]);
    a.node(json!({ "mesh": mesh }));
    a
}
