//! `lumis export`: a scene (JSON, a mesh file or Mitsuba XML) as a Mitsuba 3 XML scene, with the
//! meshes Mitsuba cannot read from the scene's own files written as PLY beside it
//! (`lumis::scene::mitsuba::export`, docs/mitsuba.md "Export").

use crate::cli::ExportArgs;
use anyhow::{Context, bail};
use lumis::scene::mitsuba::export::{ExportOptions, write_export};

/// Exports the scene and lists the files written on stderr.
pub fn export(args: &ExportArgs) -> anyhow::Result<()> {
    if args.spp == Some(0) {
        bail!("--spp must be at least 1");
    }
    if !lumis::scene::mitsuba::is_mitsuba_file(&args.output) {
        bail!(
            "{}: the output must be a .xml file (a Mitsuba 3 scene)",
            args.output.display()
        );
    }
    if let Some(dir) = args.output.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        bail!("{}: no such folder", dir.display());
    }
    lumis_app::scene_file::set_studio(!args.no_studio);
    lumis_app::scene_file::set_defines(&args.scene, args.define.clone(), args.spp);
    let loaded = lumis_app::scene_file::load_scene_file(&args.scene)?;
    let mut options = ExportOptions {
        spp: args.spp.or(loaded.spp),
        ..ExportOptions::default()
    };
    if let Some(rr) = loaded.rr_depth {
        options.rr_depth = rr;
    }
    let written = write_export(&loaded.desc, &args.output, &options)
        .map_err(|e| e.in_file(&args.scene))
        .with_context(|| format!("cannot export to {}", args.output.display()))?;
    for f in written {
        eprintln!("wrote {}", f.display());
    }
    Ok(())
}
