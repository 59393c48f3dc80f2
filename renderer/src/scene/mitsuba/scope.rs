//! What lumis refuses as out of scope, stated once: polarization, participating media, curves and
//! hair, signed distance fields, measured BSDFs, and the integrators that render no image. Every
//! object of a Mitsuba file is checked here when it is read ([`super::plugin::Plugin::new`], for
//! the object and for the objects nested in it), before any plugin's own mapping, so such a file
//! is one error at the object, with the words "out of scope" and the reason, never a message
//! that suggests a missing feature. Anything else lumis does not map is a defect of the importer
//! (docs/mitsuba.md, "Out of scope").

use super::plugin::OBJECT_TAGS;
use super::xml::Element;
use crate::scene::error::SceneError;

/// Why `<tag type="ty">` is out of scope, or `None` if it is not.
pub fn out_of_scope(tag: &str, ty: &str) -> Option<&'static str> {
    const POLARIZATION: &str = "polarization is not planned (lumis renders unpolarized RGB)";
    const MEDIA: &str = "participating media are not planned (lumis renders surfaces in vacuum)";
    const CURVES: &str = "curves and hair are not planned";
    Some(match (tag, ty) {
        ("bsdf", "pplastic" | "polarizer" | "measured_polarized") => POLARIZATION,
        ("integrator", "stokes") => POLARIZATION,
        (_, t) if t.ends_with("_polarized") => POLARIZATION,
        ("medium" | "phase" | "volume", _) => MEDIA,
        ("texture", "volume") => MEDIA,
        ("integrator", "volpath" | "volpathmis" | "prbvolpath") => MEDIA,
        ("shape", "bsplinecurve" | "linearcurve") | ("bsdf", "hair") => CURVES,
        ("shape", "sdfgrid") => "signed distance fields (sdfgrid) are not planned",
        ("bsdf", "measured") => "measured BSDFs are not planned",
        ("integrator", "aov" | "depth") => {
            "lumis renders images of radiance; an integrator of AOVs or depths is not planned"
        }
        _ => return None,
    })
}

/// The error for `el` if it, or an object nested directly in it, is out of scope.
pub fn check(el: &Element) -> Result<(), SceneError> {
    for e in std::iter::once(el).chain(el.children.iter()) {
        if !OBJECT_TAGS.contains(&e.tag.as_str()) {
            continue;
        }
        let ty = e.value("type").unwrap_or("");
        if let Some(why) = out_of_scope(&e.tag, ty) {
            return Err(e
                .pos
                .error(format!("<{} type=\"{ty}\"> is out of scope: {why}", e.tag)));
        }
    }
    Ok(())
}
