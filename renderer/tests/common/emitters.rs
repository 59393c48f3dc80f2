//! Pieces of the textured-emitter scenes shared by `renderer/tests/textured_emission.rs` (CPU) and
//! `renderer/tests/gpu/textured_emission.rs` (GPU): the fanned mesh panel with irregular texture
//! coordinates, the 4×4 emission bitmap, the irregular pentagon, scratch folders and light names.

use glam::{DVec3, Vec3};
use lumis::image_io::Image;
use lumis::lights::Light;
use std::path::PathBuf;

/// A fresh scratch folder `temp_dir()/lumis-<test>-<pid>-<name>`, emptied if it exists.
pub fn scratch_dir(test: &str, name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-{test}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A planar panel of 4 triangles fanned around `centre` from the 4 `corners` (in order around
/// it), wound so that its normal is `facing`, with irregular texture coordinates ([`PANEL_VT`],
/// the centre's last).
pub struct Panel {
    /// The corners, in order around the centre.
    pub corners: [DVec3; 4],
    /// The fan's shared vertex.
    pub centre: DVec3,
    /// The side the triangles' winding makes their normal point to.
    pub facing: DVec3,
}

/// The panel's `vt` values as written to the file (OBJ convention, `v` up).
pub const PANEL_VT: [[f64; 2]; 5] = [
    [0.1, 0.2],
    [0.9, 0.05],
    [0.8, 0.95],
    [0.05, 0.8],
    [0.55, 0.4],
];

impl Panel {
    /// The panel of the emitter scenes: leaning over the floor, facing (0, −1, −1)/√2.
    pub fn leaning() -> Panel {
        Panel {
            corners: [
                DVec3::new(-0.8, 0.15, 2.5),
                DVec3::new(0.6, 0.15, 2.5),
                DVec3::new(0.6, 1.15, 1.5),
                DVec3::new(-0.8, 1.15, 1.5),
            ],
            centre: DVec3::new(-0.2, 0.55, 2.1),
            facing: DVec3::new(0.0, -1.0, -1.0).normalize(),
        }
    }

    /// Its triangles as vertex indices (corners 0–3, centre 4).
    pub fn triangles(&self) -> Vec<[usize; 3]> {
        (0..4)
            .map(|i| {
                let t = [i, (i + 1) % 4, 4];
                let (p0, p1, p2) = (self.vertex(t[0]), self.vertex(t[1]), self.vertex(t[2]));
                if (p1 - p0).cross(p2 - p0).dot(self.facing) > 0.0 {
                    t
                } else {
                    [t[1], t[0], t[2]]
                }
            })
            .collect()
    }

    /// Vertex `i`: corner `i`, or the centre for 4.
    pub fn vertex(&self, i: usize) -> DVec3 {
        if i == 4 { self.centre } else { self.corners[i] }
    }

    /// The panel as OBJ text, with its texture coordinates.
    pub fn obj(&self) -> String {
        let mut s = String::new();
        for i in 0..5 {
            let v = self.vertex(i);
            s += &format!("v {} {} {}\n", v.x, v.y, v.z);
        }
        for vt in PANEL_VT {
            s += &format!("vt {} {}\n", vt[0], vt[1]);
        }
        for t in self.triangles() {
            let [a, b, c] = t.map(|i| i + 1);
            s += &format!("f {a}/{a} {b}/{b} {c}/{c}\n");
        }
        s
    }

    /// Texture coordinates lumis gives the panel's point hit by `(o, d)` (OBJ's `v` flipped to
    /// `1 − v`), and the ray parameter; `None` on a miss. f64, Möller–Trumbore.
    pub fn uv(&self, o: DVec3, d: DVec3) -> Option<(f64, [f64; 2])> {
        for t in self.triangles() {
            let [p0, p1, p2] = t.map(|i| self.vertex(i));
            let (e1, e2) = (p1 - p0, p2 - p0);
            let pv = d.cross(e2);
            let det = e1.dot(pv);
            let tv = o - p0;
            let b1 = tv.dot(pv) / det;
            let qv = tv.cross(e1);
            let b2 = d.dot(qv) / det;
            let dist = e2.dot(qv) / det;
            if b1 >= 0.0 && b2 >= 0.0 && b1 + b2 <= 1.0 && dist > 0.0 {
                let vt = t.map(|i| [PANEL_VT[i][0], 1.0 - PANEL_VT[i][1]]);
                let w = [1.0 - b1 - b2, b1, b2];
                let uv = [0, 1].map(|c| (0..3).map(|k| w[k] * vt[k][c]).sum());
                return Some((dist, uv));
            }
        }
        None
    }
}

/// A 4×4 emission bitmap of strongly varying colours (linear), every texel positive, no symmetry
/// (a flipped axis changes it), so the bilinear value and the light it casts change a lot.
pub fn emission_texels() -> Image {
    let data = (0..16)
        .map(|i| {
            let (x, y) = (i % 4, i / 4);
            Vec3::new(
                if (x + y) % 2 == 0 { 4.0 } else { 0.2 },
                if x < 2 { 3.0 } else { 0.3 },
                0.5 + y as f32,
            )
        })
        .collect();
    Image {
        width: 4,
        height: 4,
        data,
    }
}

/// The vertices (JSON arrays) of an irregular pentagon in the leaning panel's orientation:
/// x = +x, y = (0, −1, 1)/√2, x × y = (0, −1, −1)/√2.
pub fn pentagon() -> Vec<String> {
    let (px, py) = (DVec3::X, DVec3::new(0.0, -1.0, 1.0).normalize());
    [0.0f64, 1.3, 2.4, 3.7, 5.0]
        .iter()
        .zip([0.5, 0.6, 0.45, 0.55, 0.5])
        .map(|(a, r)| {
            let v = DVec3::new(1.6, 0.7, 1.6) + r * a.cos() * px + r * a.sin() * py;
            format!("[{}, {}, {}]", v.x, v.y, v.z)
        })
        .collect()
}

/// The light kind's name, for messages and counts.
pub fn kind(light: &Light) -> &'static str {
    light.kind_name()
}
