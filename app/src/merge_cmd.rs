//! `lumis merge`: adds the sums of part files (see [`lumis_app::part_file`]) into one part.
//!
//! Parts hold f64 sums of disjoint sample ranges, so the merge is the render of all their
//! samples up to the regrouping of f64 additions: means and variances weighted by sample count
//! come out of the summed Σx and Σx². Parts are added in the order of their first sample, so
//! the result does not depend on the order of the arguments.

use crate::cli::MergeArgs;
use crate::render_cmd::check_output_dir;
use anyhow::bail;
use lumis::engine::Film;
use lumis_app::part_file::{Part, format_ranges, union};
use std::path::PathBuf;

/// Merges the parts and writes the result, refusing parts that cannot be merged exactly.
pub fn merge(args: &MergeArgs) -> anyhow::Result<()> {
    let out = &args.output;
    let ext = out.extension().and_then(|e| e.to_str());
    if !ext.is_some_and(|e| e.eq_ignore_ascii_case("exr")) {
        bail!("{}: the merged part file must end in .exr", out.display());
    }
    check_output_dir(out)?;
    let parts = args
        .parts
        .iter()
        .map(|p| Ok((p.clone(), Part::read(p)?)))
        .collect::<anyhow::Result<Vec<_>>>()?;
    check_compatible(&parts)?;
    let first = &parts[0].1;
    let mut order: Vec<&Part> = parts.iter().map(|(_, p)| p).collect();
    order.sort_by_key(|p| p.samples[0].start);
    let mut film = Film::new(first.film.width, first.film.height);
    for part in order {
        for (sum, p) in film.pixels.iter_mut().zip(&part.film.pixels) {
            for c in 0..3 {
                sum.sum[c] += p.sum[c];
                sum.sum_sq[c] += p.sum_sq[c];
                sum.sum_even[c] += p.sum_even[c];
            }
        }
        film.spp += part.film.spp;
        film.nonfinite += part.film.nonfinite;
    }
    let samples = union(parts.iter().flat_map(|(_, p)| p.samples.clone()).collect());
    let merged = Part {
        film,
        samples,
        provenance: first.provenance.clone(),
    };
    merged.write(out)?;
    println!(
        "spp={} samples={} parts={} nonfinite={}",
        merged.film.spp,
        format_ranges(&merged.samples),
        parts.len(),
        merged.film.nonfinite
    );
    Ok(())
}

/// Same size and provenance as the first part, and no sample index in two parts; the error
/// names the file at fault.
fn check_compatible(parts: &[(PathBuf, Part)]) -> anyhow::Result<()> {
    let (first_path, first) = &parts[0];
    let first_name = first_path.display();
    for (path, part) in &parts[1..] {
        let (a, b) = (&first.film, &part.film);
        if (a.width, a.height) != (b.width, b.height) {
            bail!(
                "{} is {}x{} but {first_name} is {}x{}",
                path.display(),
                b.width,
                b.height,
                a.width,
                a.height
            );
        }
        if let Some((field, theirs, mine)) = part.provenance.difference(&first.provenance) {
            bail!(
                "{}: {field} {theirs} differs from {first_name}'s {mine}",
                path.display()
            );
        }
    }
    let mut spans: Vec<(std::ops::Range<u32>, usize)> = parts
        .iter()
        .enumerate()
        .flat_map(|(i, (_, p))| p.samples.iter().map(move |r| (r.clone(), i)))
        .collect();
    spans.sort_by_key(|(r, _)| r.start);
    for w in spans.windows(2) {
        let ((a, i), (b, j)) = (&w[0], &w[1]);
        if b.start < a.end {
            let name = |k: usize| parts[k].0.display();
            bail!(
                "{}: samples {}..{} overlap {}'s {}..{} (each sample index may be in one part only)",
                name(*j),
                b.start,
                b.end,
                name(*i),
                a.start,
                a.end
            );
        }
    }
    Ok(())
}
