//! Textured materials in every strategy (issue 17, item 5), against a closed form: a 4 × 4
//! diffuse quad whose albedo is a checkerboard (8 × 8 squares of albedo a0 and a1), seen from
//! above under a constant sky L. The plane cannot see itself, so every point reflects exactly
//! a(uv)·L at `max_depth` 2 and −1. Pixels whose four corners (camera rays through them) land on
//! squares of one colour are grouped by colour; each group's mean is compared with a·L per
//! channel, for every strategy and light-sampling method (z-test, family-wise α = 0.01,
//! Šidák-corrected over all comparisons; seeds fixed below). What this catches: textures not
//! evaluated (the mean albedo everywhere is wrong by ±(a1 − a0)/2 in both groups), UVs off by a
//! square or flipped (each group would mix colours), a strategy that evaluates the material
//! without its texture (light sampling, MIS).

mod common;

use common::{METHODS, STRATEGIES, Tally, build, render};
use glam::Vec2;
use lumis::integrator::Settings;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::textures::Texture;

const SIZE: u32 = 48;
const A0: [f32; 3] = [0.8, 0.5, 0.2];
const A1: [f32; 3] = [0.1, 0.3, 0.6];
const SKY: f32 = 1.5;

#[test]
fn checkerboard_albedo_matches_its_closed_form_in_every_strategy() {
    let json = format!(
        r#"{{
  "camera": {{"from": [0.3, 3, -1.2], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 60,
             "width": {SIZE}, "height": {SIZE}}},
  "max_depth": -1,
  "background": [{SKY}, {SKY}, {SKY}],
  "materials": {{"floor": {{"type": "diffuse", "albedo": {{"type": "checkerboard",
      "color0": {A0:?}, "color1": {A1:?}, "uv_scale": [4, 4]}}}}}},
  "shapes": [{{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
              "material": "floor"}}]
}}"#
    );
    let scene = build(&json);
    let Some(Texture::Checkerboard(checker)) = scene.material_textures[0]
        .as_ref()
        .and_then(|t| t.albedo.clone())
    else {
        panic!("the floor's albedo is a checkerboard texture");
    };
    // The quad's uv of the floor point a camera ray through pixel position (x, y) meets.
    let uv_at = |x: f32, y: f32| -> Option<Vec2> {
        let ray = scene.camera.ray(x, y);
        let t = -ray.o.y / ray.d.y;
        let p = ray.o + t * ray.d;
        let uv = Vec2::new((p.z + 2.0) / 4.0, (p.x + 2.0) / 4.0);
        (t > 0.0 && uv.min_element() > 0.0 && uv.max_element() < 1.0).then_some(uv)
    };
    // Pixel indices by colour: all four corners on squares of the same colour.
    let mut groups: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let corners: Option<Vec<bool>> = [(0, 0), (1, 0), (0, 1), (1, 1)]
                .iter()
                .map(|&(dx, dy)| {
                    uv_at((x + dx) as f32, (y + dy) as f32).map(|uv| checker.is_color1(uv))
                })
                .collect();
            if let Some(c) = corners
                && c.iter().all(|&b| b == c[0])
            {
                groups[c[0] as usize].push((y * SIZE + x) as usize);
            }
        }
    }
    assert!(
        groups.iter().all(|g| g.len() > 200),
        "{} / {} pixels",
        groups[0].len(),
        groups[1].len()
    );

    let comparisons = STRATEGIES.len() * METHODS.len() * 2 * 3;
    let mut tally = Tally::new(normal_two_sided_critical(sidak(0.01, comparisons)));
    for (k, strategy) in STRATEGIES.into_iter().enumerate() {
        for (m, light_sampling) in METHODS.into_iter().enumerate() {
            let settings = Settings {
                strategy,
                light_sampling,
                ..Settings::default()
            };
            let r = render(&scene, settings, 64, (1 + 10 * k + m) as u32);
            let film = r.film();
            let (mean, var) = (film.mean(), film.variance_of_mean());
            for (colour, (pixels, albedo)) in groups.iter().zip([A0, A1]).enumerate() {
                for c in 0..3 {
                    let means: Vec<f64> = pixels.iter().map(|&i| mean[i][c] as f64).collect();
                    let vars: Vec<f64> = pixels.iter().map(|&i| var[i][c]).collect();
                    let expected = (albedo[c] * SKY) as f64;
                    let what = format!("{strategy:?} {light_sampling:?} colour{colour} ch {c}");
                    tally.compare(&what, &means, &vars, expected);
                }
            }
        }
    }
    tally.finish("checkerboard_albedo", comparisons);
}
