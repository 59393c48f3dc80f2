//! Materials made of other materials: a `mix` (one of two chosen per hit by a weight,
//! [`crate::materials::mix`]) and a `two_sided` pair (a front and a back material, Mitsuba's
//! `twosided` with two BSDFs, [`crate::materials::two_sided`]). Each is parsed with the other
//! materials; its names are looked up once every material is known ([`resolve_parts`]), which
//! checks the rules both share (no material contains itself, no part has an opacity) and each
//! one's own (a mix's materials agree on `two_sided`; a pair's parts do not transmit).

use super::desc::{MixDesc, NamedMaterial, TextureDesc};
use super::error::SceneError;
use super::parse_texture::{TextureLoader, TextureUse, texture_at};
use super::walk::{Obj, array, join};

/// A mix or a pair as parsed, before its material names are looked up.
pub(super) enum Pending {
    Mix {
        names: [String; 2],
        weight: f64,
        weight_texture: Option<TextureDesc>,
        mitsuba: bool,
    },
    /// A two-sided pair's front and back.
    Sides([String; 2]),
}

/// A mix's `materials` (two names) and `weight` (a number or a scalar texture, in [0, 1]).
pub(super) fn parse_mix(obj: &Obj, loader: &mut TextureLoader) -> Result<Pending, SceneError> {
    let path = obj.at("materials");
    let items = array(obj.req("materials")?, &path)?;
    if items.len() != 2 {
        let msg = format!("expected 2 material names, found {}", items.len());
        return Err(SceneError::new(path, msg));
    }
    let name = |i: usize| -> Result<String, SceneError> {
        items[i].as_str().map(str::to_owned).ok_or_else(|| {
            SceneError::new(
                format!("{path}[{i}]"),
                "expected a material name (a string)",
            )
        })
    };
    let names = [name(0)?, name(1)?];
    let weight_texture = texture_at(obj, "weight", TextureUse::Weight, loader)?;
    let weight = match &weight_texture {
        Some(t) => t.mean_scalar(),
        None => {
            let w = obj.number("weight")?;
            if !(0.0..=1.0).contains(&w) {
                let msg = format!("weight {w} is outside [0, 1]");
                return Err(SceneError::new(obj.at("weight"), msg));
            }
            w
        }
    };
    let mitsuba = match obj.get("model") {
        None => false,
        Some(_) => match obj.string("model")? {
            "lumis" => false,
            "mitsuba" => true,
            other => {
                let msg = format!("unknown mix model `{other}` (expected lumis or mitsuba)");
                return Err(SceneError::new(obj.at("model"), msg));
            }
        },
    };
    Ok(Pending::Mix {
        names,
        weight,
        weight_texture,
        mitsuba,
    })
}

/// A two-sided pair's `front` and `back` (material names).
pub(super) fn parse_two_sided(obj: &Obj) -> Result<Pending, SceneError> {
    if obj.get("two_sided").is_some() {
        let msg = "a two_sided pair is two-sided by definition: its `front` and `back` apply";
        return Err(SceneError::new(obj.at("two_sided"), msg));
    }
    obj.only_keys(&["type", "front", "back", "opacity"], true)?;
    Ok(Pending::Sides([
        obj.string("front")?.to_owned(),
        obj.string("back")?.to_owned(),
    ]))
}

/// The rule of a `"model": "mitsuba"` mix's parts (at `paths`): each a material of its own (no
/// mix or pair, whose own choice would come before the blend's weighting), without a normal or
/// bump map, anisotropy or transmission, so that both parts are seen in one frame from one side
/// and the partner's BSDF is evaluated where the chosen part's delta lobe points
/// ([`crate::materials::mix::blend_delta_weight`]).
fn mitsuba_parts(
    materials: &[NamedMaterial],
    parts: [usize; 2],
    paths: &[String; 2],
) -> Result<(), SceneError> {
    for (k, &p) in parts.iter().enumerate() {
        let m = &materials[p];
        let why = if m.parts().is_some() {
            Some("a mix or two_sided pair")
        } else if m.normal_map.is_some() {
            Some("a material with a normal or bump map")
        } else if m.material.transmits() {
            Some("a transmitting material")
        } else if m.textures.alpha_v.is_some() || is_anisotropic(&m.material) {
            Some("an anisotropic material")
        } else {
            None
        };
        if let Some(why) = why {
            let msg = format!(
                "`{}` is {why}, which a mix of model mitsuba cannot hold (its parts are \
                 evaluated together in one shading frame)",
                m.name
            );
            return Err(SceneError::new(&paths[k], msg));
        }
    }
    Ok(())
}

/// Whether `m`'s roughness is anisotropic (α_u ≠ α_v).
fn is_anisotropic(m: &super::desc::MaterialDesc) -> bool {
    use super::desc::MaterialDesc;
    match m {
        MaterialDesc::Conductor { alpha, alpha_v, .. }
        | MaterialDesc::Dielectric { alpha, alpha_v, .. } => alpha_v.is_some_and(|v| v != *alpha),
        _ => false,
    }
}

/// What a material made of others is called in messages.
fn kind(m: &NamedMaterial) -> &'static str {
    if m.sides.is_some() {
        "two_sided pair"
    } else {
        "mix"
    }
}

/// The JSON paths of the two names of material `name` (`pending`'s kind): a mix's
/// `materials[0]` and `materials[1]`, a pair's `front` and `back`.
fn part_paths(obj: &Obj, name: &str, pending: &Pending) -> [String; 2] {
    let at = obj.at(name);
    match pending {
        Pending::Mix { .. } => {
            let m = join(&at, "materials");
            [format!("{m}[0]"), format!("{m}[1]")]
        }
        Pending::Sides(_) => [join(&at, "front"), join(&at, "back")],
    }
}

/// Where a rule about the parts of material `name` is reported: a mix's `materials`, a pair
/// itself.
fn parts_path(obj: &Obj, m: &NamedMaterial) -> String {
    match m.mix {
        Some(_) => join(&obj.at(&m.name), "materials"),
        None => obj.at(&m.name),
    }
}

/// Looks up the names of every mix and pair, then checks that none contains itself (directly
/// or through others), that a mix's materials agree on `two_sided` (dielectrics have no sides;
/// a pair is two-sided) and that nothing under a pair transmits, and gives each the description
/// of the material that stands in for it: a mix's favoured by its mean weight, a pair's front.
pub(super) fn resolve_parts(
    obj: &Obj,
    materials: &mut [NamedMaterial],
    pending: Vec<Option<Pending>>,
) -> Result<(), SceneError> {
    let names: Vec<String> = materials.iter().map(|m| m.name.clone()).collect();
    // The mixes of model mitsuba, checked once every part is known.
    let mut blends = Vec::new();
    for (i, p) in pending.into_iter().enumerate() {
        let Some(p) = p else { continue };
        let paths = part_paths(obj, &names[i], &p);
        let (Pending::Mix { names: parts, .. } | Pending::Sides(parts)) = &p;
        let mut index = [0; 2];
        for (k, name) in parts.iter().enumerate() {
            index[k] = names.iter().position(|n| n == name).ok_or_else(|| {
                SceneError::new(
                    &paths[k],
                    format!("unknown material `{name}` (defined: {})", names.join(", ")),
                )
            })?;
            if materials[index[k]].opacity.is_some() {
                let what = match p {
                    Pending::Mix { .. } => "a mix's materials",
                    Pending::Sides(_) => "a two_sided pair's sides",
                };
                let msg = format!(
                    "material `{name}` has an opacity, and {what} cannot: a ray meets or passes \
                     a surface before the material is chosen (give the opacity to `{}`)",
                    names[i]
                );
                return Err(SceneError::new(&paths[k], msg));
            }
        }
        match p {
            Pending::Mix {
                weight,
                weight_texture,
                mitsuba,
                ..
            } => {
                if mitsuba {
                    blends.push((index, paths));
                }
                materials[i].mix = Some(MixDesc {
                    materials: index,
                    weight,
                    weight_texture,
                    mitsuba,
                });
            }
            Pending::Sides(_) => materials[i].sides = Some(index),
        }
    }
    for (parts, paths) in blends {
        mitsuba_parts(materials, parts, &paths)?;
    }
    // Depth-first over the parts (an explicit stack; 1 = on the stack, 2 = done), so every
    // material is finished after its parts: `sides` then holds, per material, the `two_sided`
    // of the sided materials under it (`None`: dielectrics only) and `transmits` whether any
    // transmits.
    let n = materials.len();
    let mut state = vec![0u8; n];
    let mut sides: Vec<Option<bool>> = vec![None; n];
    let mut transmits = vec![false; n];
    for root in 0..n {
        if state[root] != 0 {
            continue;
        }
        let mut stack = vec![(root, 0usize)];
        state[root] = 1;
        while let Some(&mut (m, ref mut next)) = stack.last_mut() {
            let child = materials[m].parts().and_then(|p| p.get(*next).copied());
            if let Some(c) = child {
                *next += 1;
                match state[c] {
                    0 => {
                        state[c] = 1;
                        stack.push((c, 0));
                    }
                    1 => {
                        let from = stack.iter().position(|&(s, _)| s == c).unwrap_or(0);
                        let cycle: Vec<&str> = stack[from..]
                            .iter()
                            .map(|&(s, _)| names[s].as_str())
                            .chain([names[c].as_str()])
                            .collect();
                        let msg = format!(
                            "a {} cannot contain itself: {}",
                            kind(&materials[m]),
                            cycle.join(" → ")
                        );
                        return Err(SceneError::new(parts_path(obj, &materials[m]), msg));
                    }
                    _ => {}
                }
                continue;
            }
            stack.pop();
            state[m] = 2;
            let me = &materials[m];
            (sides[m], transmits[m]) = match (&me.mix, me.sides) {
                (None, None) => {
                    let t = me.material.transmits();
                    ((!t).then_some(me.two_sided), t)
                }
                (Some(mix), _) => {
                    let [a, b] = mix.materials;
                    let agreed = match (sides[a], sides[b]) {
                        (Some(x), Some(y)) if x != y => {
                            let msg = format!(
                                "its materials differ in `two_sided` (`{}` is {x}, `{}` is {y}): \
                                 a mix has one set of sides",
                                names[a], names[b]
                            );
                            return Err(SceneError::new(parts_path(obj, me), msg));
                        }
                        (x, y) => x.or(y),
                    };
                    (agreed, transmits[a] || transmits[b])
                }
                (None, Some(parts)) => {
                    if let Some(k) = (0..2).find(|&k| transmits[parts[k]]) {
                        let msg = format!(
                            "material `{}` transmits light (or may: a mix with a transmitting \
                             material), and a two_sided pair's sides reflect only: a \
                             transmitting material's two sides are its two media (Mitsuba's \
                             twosided refuses it too)",
                            names[parts[k]]
                        );
                        let key = ["front", "back"][k];
                        return Err(SceneError::new(join(&obj.at(&me.name), key), msg));
                    }
                    (Some(true), false)
                }
            };
        }
    }
    for i in 0..n {
        if materials[i].parts().is_none() {
            continue;
        }
        // Acyclic now, so this ends within `n` steps.
        let mut favoured = i;
        while let Some(parts) = materials[favoured].parts() {
            favoured = match &materials[favoured].mix {
                Some(mix) => parts[usize::from(mix.weight >= 0.5)],
                None => parts[0],
            };
        }
        materials[i].material = materials[favoured].material.clone();
        materials[i].two_sided = sides[i].unwrap_or(false);
    }
    Ok(())
}

#[cfg(test)]
#[path = "parse_composite_tests.rs"]
mod tests;
