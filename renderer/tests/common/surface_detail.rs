//! What the normal-map, bump-map and mask tests share (`renderer/tests/normal_map.rs`,
//! `bump_map.rs`, `mask.rs` and their GPU twins): Mitsuba scenes whose image is one exact value,
//! the leak and grazing checks of a one-sided plane under a strong map, the gallery's scenes at
//! a reduced film, a shared scene with an opacity on its materials.

use super::{STRATEGIES_AND_OPTIMAL, data_dir, reference, render};
use glam::Vec3;
use lumis::integrator::Settings;
use lumis::scene::{Scene, SceneDesc, TextureDesc, load_scene, parse_scene_in};
use lumis::textures::Texture;
use std::path::Path;
use std::sync::Arc;

/// `tests/data/mitsuba/NAME.xml`, imported.
pub fn mitsuba_desc(name: &str) -> SceneDesc {
    let path = data_dir().join("mitsuba").join(format!("{name}.xml"));
    lumis::scene::mitsuba::load(&path, &[])
        .unwrap_or_else(|e| panic!("{e}"))
        .desc
}

/// `tests/data/mitsuba/NAME.xml`, imported and built.
pub fn mitsuba_scene(name: &str) -> Arc<Scene> {
    Arc::new(Scene::from_desc(&mitsuba_desc(name)).unwrap_or_else(|e| panic!("{e}")))
}

/// The gallery's `tests/data/gallery/docs/scenes/NAME.xml`, unmodified, at `scale` of its film
/// (each side rounded, at least 1), built.
pub fn gallery_scene_at(name: &str, scale: f64) -> Scene {
    let path = data_dir().join(format!("gallery/docs/scenes/{name}.xml"));
    let params = lumis::scene::mitsuba::Params {
        defines: Vec::new(),
        spp: None,
    };
    let mut desc = lumis::scene::mitsuba::load_params(&path, &params)
        .unwrap_or_else(|e| panic!("{e}"))
        .desc;
    let scaled = |n: u32| ((n as f64 * scale).round() as u32).max(1);
    (desc.camera.width, desc.camera.height) =
        (scaled(desc.camera.width), scaled(desc.camera.height));
    Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}"))
}

/// Every pixel of `got` within `rel` (of the reference's largest channel) of
/// `tests/data/refs/REFERENCE`'s.
pub fn assert_pixels_match(got: &[Vec3], reference_file: &str, rel: f32, what: &str) {
    let want = reference(reference_file);
    assert_eq!(got.len(), want.data.len(), "{what}: size");
    for (k, (g, w)) in got.iter().zip(&want.data).enumerate() {
        assert!(
            (*g - *w).abs().max_element() <= rel * w.max_element(),
            "{what}: pixel {k} {g:?}, Mitsuba {w:?}"
        );
    }
}

/// The leak and grazing checks' scene: a one-sided rough plastic quad 2 × 2 about the origin,
/// normal +y, whose material carries `map` (a JSON member, `"normal_map": {…}` or
/// `"bump_map": {…}`, files relative to `dir`), seen from `from` with vertical field of view
/// `vfov` on a 32² film, lit by a sphere light of radius 0.25 at `light`.
pub fn plane_under_map(
    dir: &Path,
    map: &str,
    from: [f32; 3],
    vfov: f32,
    light: [f32; 3],
) -> Arc<Scene> {
    let json = format!(
        r#"{{"camera": {{"from": {from:?}, "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": {vfov},
                        "width": 32, "height": 32}},
            "materials": {{
              "bumpy": {{"type": "plastic", "albedo": [0.7, 0.7, 0.7], "alpha": 0.3,
                         "two_sided": false, {map}}}
            }},
            "shapes": [
              {{"type": "quad", "corner": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0],
                "material": "bumpy"}},
              {{"type": "sphere", "center": {light:?}, "radius": 0.25, "emission": [20, 20, 20]}}
            ]}}"#
    );
    let desc = parse_scene_in(&json, dir).unwrap_or_else(|e| panic!("{e}\n{json}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

/// A one-sided plane that the camera alone sees, lit by a light `below` it (which must reach no
/// pixel in any strategy: no light through the surface) and, as the check's power, by one
/// `above` it (which must light more than 50 of its pixels); render `i` of a strategy uses seed
/// `seed_below + i` resp. `seed_above + i`, 16 spp.
pub fn assert_no_light_through(
    below: &Arc<Scene>,
    above: &Arc<Scene>,
    seed_below: u32,
    seed_above: u32,
) {
    for (i, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
        let s = Settings {
            strategy,
            ..Settings::default()
        };
        let film = render(below, s, 16, seed_below + i as u32).film().clone();
        assert_eq!(film.nonfinite, 0);
        let lit = film
            .mean()
            .iter()
            .filter(|c| c.max_element() != 0.0)
            .count();
        assert_eq!(
            lit, 0,
            "{strategy:?}: light below the plane reached {lit} pixels"
        );
        let film = render(above, s, 16, seed_above + i as u32).film().clone();
        let lit = film.mean().iter().filter(|c| c.max_element() > 0.0).count();
        assert!(
            lit > 50,
            "{strategy:?}: the light above lit only {lit} pixels"
        );
    }
}

/// The plane scene `scene(from)` seen from three grazing viewpoints renders no non-finite sample
/// in any strategy (8 spp, seed `seed + 10·viewpoint + strategy`).
pub fn assert_finite_at_grazing_views(scene: impl Fn([f32; 3]) -> Arc<Scene>, seed: u32) {
    for (k, from) in [[0.0, 0.02, -3.0], [2.5, 0.05, 2.5], [-3.0, 0.2, 0.0]]
        .into_iter()
        .enumerate()
    {
        let scene = scene(from);
        for (i, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
            let s = Settings {
                strategy,
                ..Settings::default()
            };
            let film = render(&scene, s, 8, seed + 10 * k as u32 + i as u32)
                .film()
                .clone();
            assert_eq!(film.nonfinite, 0, "{strategy:?} from {from:?}");
        }
    }
}

/// `tests/data/scenes/NAME.json` with `opacity` on every material no emitter uses (an emitter's
/// cannot have one) and no mix uses.
pub fn with_opacity(name: &str, opacity: Option<f32>) -> Arc<Scene> {
    let mut desc = load_scene(&data_dir().join("scenes").join(format!("{name}.json")))
        .unwrap_or_else(|e| panic!("{e}"));
    let emitters: Vec<usize> = desc
        .shapes
        .iter()
        .filter(|s| s.emission.max_element() > 0.0 || s.emission_texture.is_some())
        .filter_map(|s| s.material)
        .collect();
    // A mix's or pair's parts take no opacity (their mix or pair does).
    let parts: Vec<usize> = desc
        .materials
        .iter()
        .filter_map(|m| m.parts())
        .flatten()
        .collect();
    for (i, m) in desc.materials.iter_mut().enumerate() {
        if !emitters.contains(&i) && !parts.contains(&i) {
            m.opacity = opacity.map(|a| TextureDesc {
                texture: Texture::Constant(glam::Vec3::splat(a)),
            });
        }
    }
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

/// In every strategy (render `i` of strategy `i` with seed `first_seed + i`, 4 spp), `same`
/// renders `plain`'s film bit for bit and `changed` does not (the check's power); `what` names
/// the two changes in messages, `[same, changed]`.
pub fn assert_same_bits(
    plain: &Arc<Scene>,
    same: &Arc<Scene>,
    changed: &Arc<Scene>,
    first_seed: u32,
    what: [&str; 2],
) {
    for (i, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
        let s = Settings {
            strategy,
            ..Settings::default()
        };
        let seed = first_seed + i as u32;
        let sums = |scene: &Arc<Scene>| {
            let r = render(scene, s, 4, seed);
            r.film().pixels.iter().map(|p| p.sum).collect::<Vec<_>>()
        };
        let base = sums(plain);
        assert!(base == sums(same), "{strategy:?}: {} changed bits", what[0]);
        assert!(
            base != sums(changed),
            "{strategy:?}: {} changed nothing",
            what[1]
        );
    }
}

/// `xml_two_sided.xml` three ways, for the pair tests on the CPU and the GPU: its cylinder as a
/// two-sided orange (`"two_sided": true`), as the pair of orange with itself, and as imported
/// (the pair of orange outside and gold inside).
pub fn two_sided_variants() -> [SceneDesc; 3] {
    let desc = mitsuba_desc("xml_two_sided");
    let index = |name: &str| desc.materials.iter().position(|m| m.name == name).unwrap();
    let (orange, gold) = (index("orange"), index("gold"));
    let pair = desc
        .materials
        .iter()
        .position(|m| m.sides == Some([orange, gold]))
        .expect("the cylinder's pair");
    let mut same = desc.clone();
    same.materials[pair].sides = Some([orange, orange]);
    let mut flag = desc.clone();
    assert!(!flag.materials[orange].two_sided, "imported one-sided");
    flag.materials.push(lumis::scene::NamedMaterial {
        name: "orange, two-sided".into(),
        two_sided: true,
        ..flag.materials[orange].clone()
    });
    let two_sided_orange = flag.materials.len() - 1;
    for s in &mut flag.shapes {
        if s.material == Some(pair) {
            s.material = Some(two_sided_orange);
        }
    }
    [flag, same, desc]
}
