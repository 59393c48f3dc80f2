//! Materials made of others, `mix` and `two_sided`: parsing, their rules, writing them back, and
//! their resolution per hit.

use crate::geometry::Ray;
use crate::materials::Material;
use crate::rng::Rng;
use crate::scene::Scene;
use crate::scene::desc::SceneDesc;
use crate::scene::parse::parse_scene_value;
use crate::scene::tests::{base, expect_err};
use glam::Vec3;
use serde_json::{Value, json};

/// The base scene with extra materials.
fn with_materials(extra: Value) -> Value {
    let mut s = base();
    for (k, v) in extra.as_object().unwrap() {
        s["materials"][k] = v.clone();
    }
    s
}

fn index(d: &SceneDesc, name: &str) -> usize {
    d.materials.iter().position(|m| m.name == name).unwrap()
}

#[test]
fn a_mix_names_two_materials_and_writes_back() {
    let s = with_materials(json!({
        "half": {"type": "mix", "materials": ["metal", "plastic"], "weight": 0.25},
        "nested": {"type": "mix", "materials": ["half", "white"], "weight": 0.6},
    }));
    let d = parse_scene_value(&s).unwrap();
    let (half, nested) = (index(&d, "half"), index(&d, "nested"));
    let mix = d.materials[half].mix.as_ref().unwrap();
    assert_eq!(mix.materials, [index(&d, "metal"), index(&d, "plastic")]);
    assert_eq!((mix.weight, mix.weight_texture.is_none()), (0.25, true));
    // The favoured material stands in for code that reads one BSDF: the first below ½.
    assert_eq!(
        d.materials[half].material,
        d.materials[index(&d, "metal")].material
    );
    assert_eq!(
        d.materials[nested].material,
        d.materials[index(&d, "white")].material
    );
    assert!(d.materials[half].two_sided && d.materials[half].textures.is_empty());
    assert_eq!(d.materials.iter().filter(|m| m.mix.is_some()).count(), 2);
    let again = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(again, d, "written back and parsed, the same description");
    assert_eq!(
        d.to_json()["materials"]["half"],
        json!({"type": "mix", "materials": ["metal", "plastic"], "weight": 0.25})
    );
}

#[test]
fn mix_rules() {
    let m = |v: Value| with_materials(json!({ "half": v }));
    let mix = |names: Value, weight: Value| {
        m(json!({"type": "mix", "materials": names, "weight": weight}))
    };
    let at = "materials.half";
    expect_err(
        &mix(json!(["metal"]), json!(0.5)),
        &format!("{at}.materials"),
        "expected 2",
    );
    expect_err(
        &mix(json!(["metal", "nope"]), json!(0.5)),
        &format!("{at}.materials[1]"),
        "unknown material `nope` (defined: copper, half, metal, plastic, white)",
    );
    expect_err(
        &mix(json!([1, "metal"]), json!(0.5)),
        &format!("{at}.materials[0]"),
        "expected a material name",
    );
    expect_err(
        &mix(json!(["metal", "white"]), json!(1.5)),
        &format!("{at}.weight"),
        "outside [0, 1]",
    );
    expect_err(
        &m(json!({"type": "mix", "materials": ["metal", "white"]})),
        &format!("{at}.weight"),
        "missing required key `weight`",
    );
    expect_err(
        &m(
            json!({"type": "mix", "materials": ["metal", "white"], "weight": 0.5, "two_sided": false}),
        ),
        &format!("{at}.two_sided"),
        "no sides of its own",
    );
    expect_err(
        &mix(json!(["half", "white"]), json!(0.5)),
        &format!("{at}.materials"),
        "half → half",
    );
    let cycle = with_materials(json!({
        "a": {"type": "mix", "materials": ["white", "b"], "weight": 0.5},
        "b": {"type": "mix", "materials": ["a", "metal"], "weight": 0.5},
    }));
    expect_err(
        &cycle,
        "materials.b.materials",
        "a mix cannot contain itself: a → b → a",
    );
    let mut sides = mix(json!(["metal", "white"]), json!(0.5));
    sides["materials"]["white"]["two_sided"] = json!(false);
    expect_err(&sides, &format!("{at}.materials"), "differ in `two_sided`");
    // A dielectric has no sides, so it agrees with either.
    let mut glass = with_materials(json!({
        "glass": {"type": "dielectric", "ior": 1.5},
        "half": {"type": "mix", "materials": ["glass", "white"], "weight": 0.5},
    }));
    glass["materials"]["white"]["two_sided"] = json!(false);
    let d = parse_scene_value(&glass).unwrap();
    assert!(!d.materials[index(&d, "half")].two_sided);
}

#[test]
fn a_textured_weight_is_a_scalar_texture() {
    let checker = json!({"type": "checkerboard", "color0": 0.2, "color1": 0.8});
    let s = with_materials(
        json!({"half": {"type": "mix", "materials": ["metal", "white"], "weight": checker}}),
    );
    let d = parse_scene_value(&s).unwrap();
    let mix = d.materials[index(&d, "half")].mix.as_ref().unwrap();
    assert_eq!(mix.weight, 0.5, "the texture's mean");
    assert!(mix.weight_texture.is_some());
    assert_eq!(parse_scene_value(&d.to_json()).unwrap(), d);
    let bad = json!({"type": "checkerboard", "color0": 1.5});
    let s = with_materials(
        json!({"half": {"type": "mix", "materials": ["metal", "white"], "weight": bad}}),
    );
    expect_err(
        &s,
        "materials.half.weight.color0",
        "a mix weight must lie in [0, 1]",
    );
}

/// A floor quad (y = 0, uv over [−1, 1]²) in material `m`, looked at from above.
fn floor_scene(materials: Value, m: &str) -> Scene {
    let s = json!({
        "camera": {"from": [0, 2, 0], "to": [0, 0, 0.1], "up": [0, 1, 0], "vfov_deg": 40,
                   "width": 8, "height": 8},
        "materials": materials,
        "shapes": [{"type": "quad", "corner": [-1, 0, -1], "edge_u": [2, 0, 0],
                    "edge_v": [0, 0, 2], "material": m}],
    });
    Scene::from_desc(&parse_scene_value(&s).unwrap()).unwrap()
}

/// How often `material_at` resolves to each material over `n` hits at random points of the
/// floor (seed 11), in the square `u ∈ [u0, u0 + ½]`, `v ∈ [v0, v0 + ½]`.
fn counts(scene: &Scene, (u0, v0): (f32, f32), n: usize) -> Vec<usize> {
    let mut rng = Rng::new(11, 0, 0);
    let mut counts = vec![0; scene.materials.len()];
    for _ in 0..n {
        let (u, v) = (u0 + 0.5 * rng.next_f32(), v0 + 0.5 * rng.next_f32());
        let target = Vec3::new(2.0 * u - 1.0, 0.0, 2.0 * v - 1.0);
        let hit = scene
            .accel
            .intersect(&Ray::new(target + Vec3::Y, -Vec3::Y))
            .unwrap();
        let material = scene.accel.primitives()[hit.prim as usize].material;
        let m = scene.resolve(&hit, material, false);
        assert_eq!(m, scene.resolve(&hit, material, false), "deterministic");
        assert_eq!(
            *scene.material_at(&hit, material, false),
            scene.materials[m as usize],
            "material_at is the resolved material"
        );
        counts[m as usize] += 1;
    }
    counts
}

/// Per hit, a mix resolves to one of its materials, the second as often as the weight says
/// there (binomial, |z| ≤ 5: a correct resolution fails with probability < 1e-5 over the five
/// comparisons): a constant weight, a checkerboard weight on its two squares (0.2 and 0.8, so
/// a resolution that ignored the texture's value at the hit, using its mean 0.5, fails), and a
/// nested mix, whose leaves get the product of the weights.
#[test]
fn a_mix_resolves_per_hit_by_its_weight() {
    let n = 20_000;
    let close = |k: usize, p: f64, what: &str| {
        let sd = (n as f64 * p * (1.0 - p)).sqrt();
        let z = (k as f64 - n as f64 * p) / sd;
        assert!(
            z.abs() <= 5.0,
            "{what}: {k} of {n}, expected {:.0} (z = {z:.2})",
            n as f64 * p
        );
    };
    let materials = json!({
        "a": {"type": "diffuse", "albedo": [0.1, 0.1, 0.1]},
        "b": {"type": "conductor", "alpha": 0.3, "reflectance": [0.9, 0.9, 0.9]},
        "c": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "m": {"type": "mix", "materials": ["a", "b"], "weight": 0.3},
        "nest": {"type": "mix", "materials": ["m", "c"], "weight": 0.5},
        "tex": {"type": "mix", "materials": ["a", "b"],
                "weight": {"type": "checkerboard", "color0": 0.2, "color1": 0.8}},
    });
    // Sorted by name: a, b, c, m, nest, tex.
    let scene = floor_scene(materials.clone(), "m");
    let k = counts(&scene, (0.0, 0.0), n);
    assert_eq!(k[0] + k[1], n, "only the mix's two materials");
    close(k[1], 0.3, "constant weight 0.3");
    let scene = floor_scene(materials.clone(), "tex");
    // The checkerboard's color0 fills [0, ½]², color1 [½, 1] × [0, ½].
    close(
        counts(&scene, (0.0, 0.0), n)[1],
        0.2,
        "checkerboard color0 = 0.2",
    );
    close(
        counts(&scene, (0.5, 0.0), n)[1],
        0.8,
        "checkerboard color1 = 0.8",
    );
    let scene = floor_scene(materials, "nest");
    let k = counts(&scene, (0.0, 0.0), n);
    assert_eq!(k[0] + k[1] + k[2], n, "only the leaves");
    close(k[1], 0.5 * 0.3, "nested: b = ½ · 0.3");
    close(k[2], 0.5, "nested: c = ½");
    assert!(matches!(scene.materials[2], Material::Diffuse(_)));
}

#[test]
fn a_two_sided_pair_names_front_and_back_and_writes_back() {
    let s = with_materials(json!({
        "pair": {"type": "two_sided", "front": "metal", "back": "white"},
        "veiled": {"type": "two_sided", "front": "metal", "back": "white", "opacity": 0.5},
        // A pair may hold a mix, and a mix a pair (with a two-sided partner).
        "mixed": {"type": "two_sided", "front": "half", "back": "plastic"},
        "half": {"type": "mix", "materials": ["pair", "white"], "weight": 0.5},
    }));
    let d = parse_scene_value(&s).unwrap();
    let pair = &d.materials[index(&d, "pair")];
    assert_eq!(pair.sides, Some([index(&d, "metal"), index(&d, "white")]));
    assert!(pair.two_sided && pair.mix.is_none() && pair.textures.is_empty());
    assert!(pair.opacity.is_none() && d.materials[index(&d, "veiled")].opacity.is_some());
    // The front stands in for code that reads one BSDF.
    assert_eq!(pair.material, d.materials[index(&d, "metal")].material);
    assert_eq!(
        d.materials[index(&d, "mixed")].material,
        d.materials[index(&d, "white")].material,
        "its front, the mix, favours its second at weight ½: white"
    );
    let written = d.to_json();
    assert_eq!(
        written["materials"]["veiled"],
        json!({"type": "two_sided", "front": "metal", "back": "white", "opacity": 0.5})
    );
    assert_eq!(parse_scene_value(&written).unwrap(), d);
}

#[test]
fn a_mix_keeps_its_opacity_when_written_back() {
    let s = with_materials(json!({
        "half": {"type": "mix", "materials": ["metal", "white"], "weight": 0.5, "opacity": 0.25},
    }));
    let d = parse_scene_value(&s).unwrap();
    assert_eq!(d.to_json()["materials"]["half"]["opacity"], json!(0.25));
    assert_eq!(parse_scene_value(&d.to_json()).unwrap(), d);
}

#[test]
fn two_sided_pair_rules() {
    let m = |v: Value| with_materials(json!({ "pair": v }));
    let pair =
        |front: &str, back: &str| m(json!({"type": "two_sided", "front": front, "back": back}));
    let at = "materials.pair";
    expect_err(
        &pair("metal", "nope"),
        &format!("{at}.back"),
        "unknown material `nope` (defined: copper, metal, pair, plastic, white)",
    );
    expect_err(
        &m(json!({"type": "two_sided", "front": "metal"})),
        &format!("{at}.back"),
        "missing required key `back`",
    );
    expect_err(
        &m(json!({"type": "two_sided", "front": "metal", "back": "white", "two_sided": true})),
        &format!("{at}.two_sided"),
        "two-sided by definition",
    );
    expect_err(
        &m(json!({"type": "two_sided", "front": "metal", "back": "white", "normal_map": {}})),
        &format!("{at}.normal_map"),
        "unknown key `normal_map`",
    );
    expect_err(
        &pair("pair", "white"),
        at,
        "a two_sided pair cannot contain itself: pair → pair",
    );
    // Transmitting parts: a dielectric, a thin one, a mix with one.
    for (name, v) in [
        ("glass", json!({"type": "dielectric", "ior": 1.5})),
        ("thin", json!({"type": "thin_dielectric", "ior": 1.5})),
        (
            "glassy",
            json!({"type": "mix", "materials": ["white", "glass"], "weight": 0.1}),
        ),
    ] {
        let mut s = pair("metal", name);
        s["materials"][name] = v;
        s["materials"]["glass"] = json!({"type": "dielectric", "ior": 1.5});
        expect_err(
            &s,
            &format!("{at}.back"),
            &format!("material `{name}` transmits light"),
        );
    }
    let mut masked = pair("metal", "white");
    masked["materials"]["white"]["opacity"] = json!(0.5);
    expect_err(
        &masked,
        &format!("{at}.back"),
        "a two_sided pair's sides cannot",
    );
    // A pair is two-sided: a mix of it and a one-sided material has two sets of sides.
    let mut one_sided = with_materials(json!({
        "pair": {"type": "two_sided", "front": "metal", "back": "white"},
        "half": {"type": "mix", "materials": ["pair", "plastic"], "weight": 0.5},
    }));
    one_sided["materials"]["plastic"]["two_sided"] = json!(false);
    expect_err(
        &one_sided,
        "materials.half.materials",
        "differ in `two_sided`",
    );
}

/// A pair resolves to its front for a path arriving on the front and to its back otherwise, at
/// every hit, and through a mix the mix chooses first.
#[test]
fn a_two_sided_pair_resolves_by_the_side_of_arrival() {
    let materials = json!({
        "a": {"type": "diffuse", "albedo": [0.1, 0.1, 0.1]},
        "b": {"type": "conductor", "alpha": 0.3, "reflectance": [0.9, 0.9, 0.9]},
        "c": {"type": "diffuse", "albedo": [0.7, 0.7, 0.7]},
        "m": {"type": "mix", "materials": ["pair", "c"], "weight": 0.5},
        "pair": {"type": "two_sided", "front": "a", "back": "b"},
    });
    // Sorted by name: a, b, c, m, pair.
    let scene = floor_scene(materials.clone(), "pair");
    let ray = Ray::new(Vec3::new(0.3, 1.0, -0.2), -Vec3::Y);
    let hit = scene.accel.intersect(&ray).unwrap();
    let pair = scene.accel.primitives()[hit.prim as usize].material;
    assert_eq!(scene.material_names[pair as usize], "pair");
    assert!(scene.two_sided[pair as usize]);
    assert_eq!(scene.resolve(&hit, pair, false), 0, "front: a");
    assert_eq!(scene.resolve(&hit, pair, true), 1, "back: b");
    assert_eq!(*scene.material_at(&hit, pair, true), scene.materials[1]);
    // Through the mix: the pair where the mix chooses it, then by side; c either way.
    let scene = floor_scene(materials, "m");
    let mut seen = [[0; 5]; 2];
    let mut rng = Rng::new(12, 0, 0);
    for _ in 0..200 {
        let o = Vec3::new(rng.next_f32() - 0.5, 1.0, rng.next_f32() - 0.5);
        let hit = scene.accel.intersect(&Ray::new(o, -Vec3::Y)).unwrap();
        for back in [false, true] {
            seen[back as usize][scene.resolve(&hit, 3, back) as usize] += 1;
        }
    }
    assert_eq!(
        seen[0][1] + seen[1][0] + seen[0][3] + seen[0][4],
        0,
        "{seen:?}"
    );
    assert_eq!(
        seen[0][0], seen[1][1],
        "the mix chose the pair as often from either side"
    );
    assert!(seen[0][0] > 0 && seen[0][2] > 0, "{seen:?}");
}

/// `"model": "mitsuba"` (Mitsuba's blendbsdf): parsed and written back, resolved with the other
/// part and the chosen part's probability, and refused where its parts cannot be evaluated
/// together (a part made of others, with a normal map, transmitting or anisotropic).
#[test]
fn a_mix_of_model_mitsuba_resolves_with_its_partner_and_keeps_its_rules() {
    let s = with_materials(json!({
        "blend": {"type": "mix", "materials": ["metal", "white"], "weight": 0.3,
                  "model": "mitsuba"},
    }));
    let d = parse_scene_value(&s).unwrap();
    let b = index(&d, "blend");
    assert!(d.materials[b].mix.as_ref().unwrap().mitsuba);
    assert_eq!(d.to_json()["materials"]["blend"]["model"], json!("mitsuba"));
    assert_eq!(parse_scene_value(&d.to_json()).unwrap(), d);

    let scene = Scene::from_desc(&d).unwrap();
    let (metal, white) = (index(&d, "metal") as u32, index(&d, "white") as u32);
    let mut rng = Rng::new(41, 0, 0);
    let mut seen = [0u32; 2];
    for _ in 0..200 {
        let o = Vec3::new(rng.next_f32() - 0.5, 5.0, rng.next_f32() - 0.5);
        let Some(hit) = scene.accel.intersect(&Ray::new(o, -Vec3::Y)) else {
            continue;
        };
        let (m, blend) = scene.resolve_blend(&hit, b as u32, false);
        let blend = blend.expect("a blend");
        let (partner, w) = if m == metal {
            (white, 0.7)
        } else {
            (metal, 0.3)
        };
        assert_eq!((blend.partner, blend.weight), (partner, w));
        seen[usize::from(m == white)] += 1;
        assert_eq!(m, scene.resolve(&hit, b as u32, false));
    }
    assert!(seen[0] > 0 && seen[1] > 0, "{seen:?}");
    // A plain mix has none.
    let plain = with_materials(json!({
        "blend": {"type": "mix", "materials": ["metal", "white"], "weight": 0.3},
    }));
    let plain = Scene::from_desc(&parse_scene_value(&plain).unwrap()).unwrap();
    let hit = plain
        .accel
        .intersect(&Ray::new(Vec3::new(0.1, 5.0, 0.2), -Vec3::Y))
        .unwrap();
    assert_eq!(plain.resolve_blend(&hit, b as u32, false).1, None);

    let blend = |parts: Value, extra: Value| {
        let mut m = extra;
        m["blend"] = json!({"type": "mix", "materials": parts, "weight": 0.5, "model": "mitsuba"});
        with_materials(m)
    };
    expect_err(
        &with_materials(json!({
            "blend": {"type": "mix", "materials": ["metal", "white"], "weight": 0.5,
                      "model": "pbrt"},
        })),
        "materials.blend.model",
        "unknown mix model `pbrt`",
    );
    let half = json!({"half": {"type": "mix", "materials": ["metal", "white"], "weight": 0.5}});
    expect_err(
        &blend(json!(["half", "white"]), half),
        "materials.blend.materials[0]",
        "`half` is a mix or two_sided pair",
    );
    let mapped = json!({"mapped": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5],
                                   "normal_map": {"texture": [0.5, 0.5, 1.0]}}});
    expect_err(
        &blend(json!(["metal", "mapped"]), mapped),
        "materials.blend.materials[1]",
        "normal or bump map",
    );
    let glass = json!({"glass": {"type": "dielectric", "ior": 1.5, "alpha": 0}});
    expect_err(
        &blend(json!(["glass", "white"]), glass),
        "materials.blend.materials[0]",
        "transmitting",
    );
    let brushed = json!({"brushed": {"type": "conductor", "alpha": [0.05, 0.3],
                                     "reflectance": [0.9, 0.9, 0.9]}});
    expect_err(
        &blend(json!(["brushed", "white"]), brushed),
        "materials.blend.materials[0]",
        "anisotropic",
    );
}
