//! `{"type": "mesh_attribute", "name": "vertex_color", "scale": 1}` textures (Mitsuba 3.9.1's
//! `mesh_attribute`, [`crate::textures::mesh_attribute`]) and their binding to the meshes that
//! carry the attribute, once the shapes are known: each texture gets its slot among the scene's
//! attribute names, every shape whose material (or a mix's or pair's part) reads one must be a
//! mesh whose file has it, with as many components as the slot reads and values in the slot's
//! range, and the texture's mean and maximum are its meshes'. A texture that cannot be met on a
//! mesh (a delta light's, a bump map's height, which needs a gradient) is refused.

use super::desc::{GeometryDesc, MaterialDesc, NamedMaterial, ShapeDesc, TextureDesc};
use super::error::SceneError;
use super::parse_texture::TextureUse;
use super::walk::Obj;
use crate::scene::desc::FresnelDesc;
use crate::scene::mesh::AttributeKind;
use crate::textures::mesh_attribute::is_attribute_name;
use crate::textures::{MeshAttributeTexture, Texture};
use glam::{DVec3, Vec3};
use std::collections::HashMap;

/// The texture object `obj` of type `mesh_attribute`, for a slot of `use_`.
pub(crate) fn mesh_attribute(
    obj: &Obj,
    use_: TextureUse,
) -> Result<MeshAttributeTexture, SceneError> {
    obj.only_keys(&["type", "name", "scale"], false)?;
    if use_ == TextureUse::Height {
        return Err(SceneError::new(
            obj.at("type"),
            "a bump map's height cannot be a mesh_attribute: it has no gradient (nor has \
             Mitsuba 3.9.1's)",
        ));
    }
    let name = obj.string("name")?;
    if !is_attribute_name(name) {
        return Err(SceneError::new(
            obj.at("name"),
            format!("`{name}` is not a mesh attribute's name: it must start with vertex_ or face_"),
        ));
    }
    let scale = match obj.opt_number("scale")? {
        None => 1.0,
        Some(s) if s.is_finite() && (s as f32).is_finite() => s as f32,
        Some(s) => {
            return Err(SceneError::new(
                obj.at("scale"),
                format!("scale {s} is not a finite number"),
            ));
        }
    };
    Ok(MeshAttributeTexture::new(name, scale))
}

/// Refuses a mesh attribute texture at `path` where no mesh is (a delta light's texture).
pub(crate) fn off_mesh(t: &TextureDesc, path: &str, what: &str) -> Result<(), SceneError> {
    match &t.texture {
        Texture::MeshAttribute(_) => Err(SceneError::new(
            path,
            format!("a mesh_attribute texture needs a mesh, and {what} is not one"),
        )),
        _ => Ok(()),
    }
}

/// One texture slot of a material: its key, its use, the texture.
type Slot<'a> = (&'static str, TextureUse, &'a mut TextureDesc);

/// The textured slots of `m`.
fn slots(m: &mut NamedMaterial) -> Vec<Slot<'_>> {
    let mut v: Vec<Slot<'_>> = Vec::new();
    let t = &mut m.textures;
    for (key, use_, slot) in [
        ("albedo", TextureUse::Albedo, &mut t.albedo),
        ("reflectance", TextureUse::Reflectance, &mut t.reflectance),
        ("alpha", TextureUse::Alpha, &mut t.alpha),
        ("alpha_v", TextureUse::Alpha, &mut t.alpha_v),
        ("opacity", TextureUse::Opacity, &mut m.opacity),
    ] {
        if let Some(tex) = slot {
            v.push((key, use_, tex));
        }
    }
    let thin = matches!(m.material, MaterialDesc::PrincipledThin(_));
    let gltf = matches!(m.material, MaterialDesc::GltfPbr(_));
    for (k, slot) in t.principled.iter_mut().enumerate() {
        if let Some(tex) = slot {
            let (key, use_) = if gltf {
                let param = crate::materials::gltf_pbr::GltfParam::ALL[k];
                (param.name(), TextureUse::Parameter)
            } else if thin {
                let param = crate::materials::principled_thin::ThinParam::ALL[k];
                (
                    param.name(),
                    crate::scene::parse_principled_thin::texture_use(param),
                )
            } else {
                let param = crate::materials::principled::PrincipledParam::ALL[k];
                (param.name(), TextureUse::Parameter)
            };
            v.push((key, use_, tex));
        }
    }
    if let Some(n) = &mut m.normal_map {
        let (key, use_) = match n.height_scale {
            Some(_) => ("bump_map", TextureUse::Height),
            None => ("normal_map", TextureUse::NormalMap),
        };
        v.push((key, use_, &mut n.texture));
    }
    if let Some(w) = m.mix.as_mut().and_then(|mix| mix.weight_texture.as_mut()) {
        v.push(("weight", TextureUse::Weight, w));
    }
    v
}

/// The values a bound texture met: their sum, count and per-channel maximum.
#[derive(Default)]
struct Stats {
    sum: DVec3,
    count: usize,
    max: Option<Vec3>,
}

/// Binds every mesh attribute texture of `materials` and `shapes` (module doc); returns the
/// scene's attribute names in slot order.
pub(crate) fn bind_mesh_attributes(
    materials: &mut [NamedMaterial],
    shapes: &mut [ShapeDesc],
) -> Result<Vec<String>, SceneError> {
    let mut names: Vec<String> = Vec::new();
    let mut slot_of = |t: &mut MeshAttributeTexture| {
        let i = names.iter().position(|n| *n == t.name).unwrap_or_else(|| {
            names.push(t.name.clone());
            names.len() - 1
        });
        t.slot = i as u32;
    };
    for m in materials.iter_mut() {
        for (_, _, tex) in slots(m) {
            if let Texture::MeshAttribute(a) = &mut tex.texture {
                slot_of(a);
            }
        }
    }
    for s in shapes.iter_mut() {
        if let Some(Texture::MeshAttribute(a)) = s.emission_texture.as_mut().map(|t| &mut t.texture)
        {
            slot_of(a);
        }
    }
    if names.is_empty() {
        return Ok(names);
    }

    let mut stats: HashMap<(usize, &'static str), Stats> = HashMap::new();
    let mut emission_stats: Vec<Stats> = (0..shapes.len()).map(|_| Stats::default()).collect();
    for (si, shape) in shapes.iter().enumerate() {
        if let Some(m) = shape.material {
            for mi in reached(materials, m) {
                let material = &mut materials[mi];
                let name = material.name.clone();
                for (key, use_, tex) in slots(material) {
                    if let Texture::MeshAttribute(a) = &tex.texture {
                        let at = format!("materials.{name}.{key}");
                        let what = format!("material `{name}`'s `{key}`");
                        check(
                            shape,
                            a,
                            use_,
                            &at,
                            &what,
                            stats.entry((mi, key)).or_default(),
                        )?;
                    }
                }
            }
        }
        if let Some(Texture::MeshAttribute(a)) = shape.emission_texture.as_ref().map(|t| &t.texture)
        {
            let at = format!("{}.emission", shape.json_path);
            check(
                shape,
                a,
                TextureUse::Emission,
                &at,
                "its `emission`",
                &mut emission_stats[si],
            )?;
        }
    }

    // The means and maxima, and the constants that stand in for the textures.
    for (mi, m) in materials.iter_mut().enumerate() {
        let mut means = Vec::new();
        for (key, _, tex) in slots(m) {
            if let Texture::MeshAttribute(a) = &mut tex.texture
                && let Some(s) = stats.get(&(mi, key))
            {
                set_stats(a, s);
                means.push((key, a.mean.as_dvec3()));
            }
        }
        for (key, mean) in means {
            stand_in(m, key, mean);
        }
    }
    for (shape, s) in shapes.iter_mut().zip(&emission_stats) {
        if let Some(Texture::MeshAttribute(a)) =
            shape.emission_texture.as_mut().map(|t| &mut t.texture)
        {
            set_stats(a, s);
            shape.emission = a.mean.as_dvec3();
        }
    }
    Ok(names)
}

/// Every material a shape of material `first` can show: its own and, through mixes and pairs,
/// their parts.
fn reached(materials: &[NamedMaterial], first: usize) -> Vec<usize> {
    let mut seen = vec![first];
    let mut i = 0;
    while i < seen.len() {
        if let Some(parts) = materials[seen[i]].parts() {
            for p in parts {
                if !seen.contains(&p) {
                    seen.push(p);
                }
            }
        }
        i += 1;
    }
    seen
}

/// Checks that `shape` carries `a`'s attribute as a slot of `use_` reads it (error at `at`,
/// the texture's path, naming the shape); adds its values to `stats`.
fn check(
    shape: &ShapeDesc,
    a: &MeshAttributeTexture,
    use_: TextureUse,
    at: &str,
    what: &str,
    stats: &mut Stats,
) -> Result<(), SceneError> {
    let fail = |message: String| Err(SceneError::new(at, message));
    let GeometryDesc::Mesh { mesh, file, .. } = &shape.geometry else {
        return fail(format!(
            "{what} reads the mesh attribute `{}`, but {} is not a mesh (only a mesh file's \
             vertex and face attributes can be read)",
            a.name, shape.json_path
        ));
    };
    let file = file.display();
    let Some(attr) = mesh.attributes.iter().find(|x| x.name == a.name) else {
        let have: Vec<&str> = mesh.attributes.iter().map(|x| x.name.as_str()).collect();
        let have = if have.is_empty() {
            "none".to_owned()
        } else {
            have.join(", ")
        };
        return fail(format!(
            "{what} reads the mesh attribute `{}`, which {} ({file}) does not have (its \
             attributes: {have})",
            a.name, shape.json_path
        ));
    };
    match (attr.dim, use_.is_scalar()) {
        (1, _) | (3, false) => {}
        (3, true) => {
            return fail(format!(
                "`{}` of {file} has 3 components and {what} is a scalar: Mitsuba 3.9.1 reads \
                 only a one-component attribute there",
                a.name
            ));
        }
        (d, _) => {
            return fail(format!(
                "`{}` of {file} has {d} components: a mesh_attribute reads 1 or 3",
                a.name
            ));
        }
    }
    let per = match attr.kind() {
        AttributeKind::Vertex => "vertex",
        // Counted after zero-area triangles are dropped (with their values).
        AttributeKind::Face => "kept triangle",
    };
    for (k, v) in attr.values.iter().enumerate() {
        let v = *v * a.scale;
        for x in v.to_array() {
            if let Some(problem) = use_.problem(x as f64) {
                return fail(format!(
                    "`{}` × {} at {per} {k} of {file} is {x}, which {problem}",
                    a.name, a.scale
                ));
            }
        }
        stats.sum += v.as_dvec3();
        stats.max = Some(stats.max.map_or(v, |m| m.max(v)));
    }
    stats.count += attr.values.len();
    Ok(())
}

/// Sets `a`'s mean and maximum from `s`.
fn set_stats(a: &mut MeshAttributeTexture, s: &Stats) {
    if s.count > 0 {
        a.mean = (s.sum / s.count as f64).as_vec3();
    }
    a.max = s.max.unwrap_or(Vec3::ZERO);
}

/// Sets the constant that stands in for slot `key` of `m` to `mean` (the rule of
/// [`super::desc::MaterialTextures`]: a textured slot's constant is its texture's mean).
fn stand_in(m: &mut NamedMaterial, key: &str, mean: DVec3) {
    let scalar = mean.x;
    match (&mut m.material, key) {
        (MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. }, "albedo") => {
            *albedo = mean
        }
        (MaterialDesc::Conductor { fresnel, .. }, "reflectance") => {
            *fresnel = FresnelDesc::Reflectance(mean)
        }
        (
            MaterialDesc::Conductor { alpha, .. }
            | MaterialDesc::Plastic { alpha, .. }
            | MaterialDesc::Dielectric { alpha, .. },
            "alpha",
        ) => *alpha = scalar,
        (
            MaterialDesc::Conductor { alpha_v, .. } | MaterialDesc::Dielectric { alpha_v, .. },
            "alpha_v",
        ) => *alpha_v = Some(scalar),
        (_, "weight") => {
            if let Some(mix) = &mut m.mix {
                mix.weight = scalar;
            }
        }
        (MaterialDesc::Principled(p), "albedo") => p.base_color = mean,
        (MaterialDesc::Principled(p), key) => {
            let params = crate::materials::principled::PrincipledParam::ALL;
            if let Some(k) = params.iter().position(|q| q.name() == key) {
                p.scalars[k] = scalar;
            }
        }
        (MaterialDesc::GltfPbr(p), "albedo") => p.base_color = mean,
        (MaterialDesc::GltfPbr(p), key) => {
            let params = crate::materials::gltf_pbr::GltfParam::ALL;
            if let Some(k) = params.iter().position(|q| q.name() == key) {
                p.scalars[k] = scalar;
            }
        }
        (MaterialDesc::PrincipledThin(p), "albedo") => p.base_color = mean,
        (MaterialDesc::PrincipledThin(p), key) => {
            let params = crate::materials::principled_thin::ThinParam::ALL;
            if let Some(k) = params.iter().position(|q| q.name() == key) {
                p.scalars[k] = scalar;
            }
        }
        // Maps and opacity have no constant.
        _ => {}
    }
}

#[cfg(test)]
#[path = "parse_mesh_attribute_tests.rs"]
mod tests;
