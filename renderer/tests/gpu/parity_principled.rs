//! Parity of the principled's WGSL twin (`materials/principled.wgsl`, `materials/gtr1.wgsl`) with
//! `materials/principled.rs`: eval, pdf and sampling of principled BSDFs that exercise every lobe
//! and both sides, at random direction pairs (seed 19).

use crate::gpu_common;
use glam::{Vec2, Vec3};
use gpu_common::parity::*;
use gpu_common::*;
use lumis::gpu::GpuScene;
use lumis::materials::Material;
use lumis::rng::Rng;
use serde_json::json;

/// The principled BSDFs compared, as the scene format writes them.
fn configs() -> Vec<serde_json::Value> {
    vec![
        json!({"type": "principled"}),
        json!({"type": "principled", "base_color": [0.9, 0.6, 0.3], "metallic": 0.8,
               "roughness": 0.35, "anisotropic": 0.7, "spec_tint": 0.5}),
        json!({"type": "principled", "base_color": [0.8, 0.2, 0.15], "roughness": 0.2,
               "specular": 0.7, "spec_tint": 0.4, "sheen": 0.8, "sheen_tint": 0.6,
               "clearcoat": 0.8, "clearcoat_gloss": 0.5, "flatness": 0.4}),
        json!({"type": "principled", "base_color": [0.8, 0.9, 1.0], "spec_trans": 0.9, "eta": 1.5,
               "roughness": 0.3, "metallic": 0.05, "sheen": 0.3}),
        json!({"type": "principled", "base_color": [0.2, 0.6, 0.9], "spec_trans": 1.0, "eta": 0.8,
               "roughness": 0.5, "clearcoat": 0.5, "main_specular_sampling_rate": 0.5,
               "clearcoat_sampling_rate": 3, "diffuse_reflectance_sampling_rate": 2}),
    ]
}

/// A unit direction at a random cosine in (−1, 1) (or (0, 1) where `upper`), random azimuth.
fn direction(r: &mut Rng, upper: bool) -> Vec3 {
    let z = if upper {
        r.next_f32().max(1e-3)
    } else {
        2.0 * r.next_f32() - 1.0
    };
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * r.next_f32();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// eval and pdf at random pairs (both sides for the transmitting ones), and the sample drawn with
/// the same random numbers: direction, weight, pdf and η'. Tolerances: 2e-4 relative, with an
/// absolute floor of 1e-7 of each value's largest magnitude over the test (the CPU sums a
/// refraction's half vector in f64, the GPU in f32: in a lobe's far tail, where that sum nearly
/// cancels, the two differ by more than any relative bound, on values 1e7 below the peak). A
/// sample whose lobe choice or validity sits within 1e-4 of a boundary is left out and counted.
#[test]
fn principled_matches() {
    let Some(ctx) = context() else {
        return;
    };
    let mut materials = serde_json::Map::new();
    for (i, c) in configs().into_iter().enumerate() {
        materials.insert(format!("p{i}"), c);
    }
    let desc = json!({
        "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
        "materials": materials,
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "p0"}]
    });
    let scene = build(&desc.to_string());
    let list: Vec<(Material, usize)> = (0..configs().len())
        .map(|i| {
            let index = scene
                .material_names
                .iter()
                .position(|n| *n == format!("p{i}"))
                .unwrap();
            (scene.materials[index].clone(), index)
        })
        .collect();
    let gpu = GpuScene::new(ctx, scene).expect("upload");
    let mut r = Rng::new(19, 0, 0);
    let items = 4 * N;
    let mut inputs = Vec::with_capacity(3 * items);
    for k in 0..items {
        let (m, index) = &list[k % list.len()];
        let wo = direction(&mut r, !m.transmits());
        let wi = direction(&mut r, false);
        inputs.push([wo.x, wo.y, wo.z, *index as f32]);
        inputs.push([wi.x, wi.y, wi.z, k as f32]);
        inputs.push([r.next_f32(), r.next_f32(), r.next_f32(), 0.0]);
    }
    let out = run(
        &gpu,
        "let m = materials[u32(inp(0u).w)]; let wo = inp(0u).xyz; let wi = inp(1u).xyz;
         let u = inp(2u);
         outp(0u, vec4f(material_eval(m, wo, wi), material_pdf(m, wo, wi)));
         let s = material_sample(m, wo, u.x, u.yz);
         outp(1u, vec4f(s.wi, select(-1.0, s.pdf, s.ok)));
         outp(2u, vec4f(s.weight, s.eta));",
        &inputs,
        3,
        3,
    );
    let scale = |f: &dyn Fn(&[[f32; 4]]) -> f32| out.chunks(3).map(f).fold(0.0f32, f32::max);
    let eval_scale = scale(&|o| o[0][..3].iter().fold(0.0f32, |a, b| a.max(b.abs())));
    let pdf_scale = scale(&|o| o[0][3].abs());
    let mut eval = Compare::new("principled eval", 2e-4, 1e-7 * eval_scale);
    let mut pdf = Compare::new("principled pdf", 2e-4, 1e-7 * pdf_scale);
    let mut sample = Compare::new("principled sample", 2e-4, 1e-5);
    let (mut sampled, mut ambiguous, mut none) = (0, 0, 0);
    let mut crossings = 0;
    for (i, o) in inputs.chunks(3).zip(out.chunks(3)) {
        let k = i[1][3] as usize;
        let m = &list[k % list.len()].0;
        let wo = Vec3::from_slice(&i[0][..3]);
        let wi = Vec3::from_slice(&i[1][..3]);
        let what = format!("{m:?} wo {wo} wi {wi}");
        let f = m.eval(wo, wi);
        for c in 0..3 {
            eval.scalar(o[0][c], f[c], &what);
        }
        pdf.scalar(o[0][3], m.pdf(wo, wi), &what);
        let (u_lobe, u) = (i[2][0], Vec2::new(i[2][1], i[2][2]));
        let s = m.sample(wo, u_lobe, u);
        let gpu_ok = o[1][3] >= 0.0;
        match s {
            Some(s) if gpu_ok => {
                sampled += 1;
                crossings += usize::from(s.wi.z * wo.z < 0.0);
                let what = format!("{what} u {u_lobe} {u}");
                for (g, w) in o[1][..3].iter().zip(s.wi.to_array()) {
                    sample.scalar(*g, w, &format!("wi, {what}"));
                }
                // Weights and pdfs as relative quantities.
                let mut rel = Compare::new("", 2e-4, 0.0);
                rel.scalar(o[1][3], s.pdf, &what);
                for (g, w) in o[2][..3].iter().zip(s.weight.to_array()) {
                    rel.scalar(*g, w, &what);
                }
                rel.scalar(o[2][3], s.eta, &what);
                if rel.bad > 0 {
                    ambiguous += 1;
                }
            }
            None if !gpu_ok => none += 1,
            // One side's lobe choice or validity test fell the other way.
            _ => ambiguous += 1,
        }
    }
    eprintln!(
        "principled: {sampled} samples compared ({crossings} crossing the surface), {none} \
         refused by both, {ambiguous} different (a lobe boundary, a validity edge or a weight \
         beyond 2e-4)"
    );
    assert!(
        sampled > items / 2 && crossings > 1000,
        "{sampled} {crossings}"
    );
    assert!(ambiguous < items / 500, "{ambiguous} of {items}");
    eval.finish(0);
    pdf.finish(0);
    sample.finish(0);
}

/// Programs with a principled that does not transmit (alone: no transmission code; beside a thin
/// sheet: transmission code without refraction) compile and render what the CPU renders from
/// the same seed, in every strategy (relMSE below the same-seed check's 1e-6).
#[test]
fn reflection_only_principled_programs_render_as_the_cpu() {
    if context().is_none() {
        return;
    }
    for with_sheet in [false, true] {
        let mut materials = serde_json::Map::new();
        let mut shapes = Vec::new();
        for (i, c) in configs().into_iter().take(3).enumerate() {
            materials.insert(format!("p{i}"), c);
            shapes.push(json!({"type": "sphere", "center": [i as f64 - 1.0, 0.4, 0], "radius": 0.4, "material": format!("p{i}")}));
        }
        materials.insert(
            "floor".into(),
            json!({"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}),
        );
        shapes.push(json!({"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "floor"}));
        shapes.push(json!({"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [8, 8, 8]}));
        if with_sheet {
            materials.insert(
                "sheet".into(),
                json!({"type": "thin_dielectric", "ior": 1.5}),
            );
            shapes.push(json!({"type": "quad", "corner": [-1.5, 0, -1], "edge_u": [3, 0, 0], "edge_v": [0, 1.2, 0], "material": "sheet"}));
        }
        let desc = json!({
            "camera": {"from": [0, 1.2, -4], "to": [0, 0.4, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 32, "height": 24},
            "background": [0.2, 0.2, 0.25],
            "materials": materials,
            "shapes": shapes
        });
        let scene = build(&desc.to_string());
        assert_eq!(scene.has_transmission(), with_sheet);
        for strategy in crate::common::STRATEGIES {
            let what = format!("principled without transmission, sheet {with_sheet}, {strategy:?}");
            let settings = lumis::integrator::Settings {
                strategy,
                ..Default::default()
            };
            let r = gpu_common::images::same_seed_check(&what, &scene, settings).expect("a GPU");
            if let Err(e) = r {
                panic!("{e}");
            }
        }
    }
}
