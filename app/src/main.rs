//! `lumis`: the command line of the lumis path tracer: `render`, `compare`, `bench`, `view`,
//! `merge` and `export`. The arguments are in `cli.rs`, each command in its own `*_cmd.rs`; the
//! viewer, the part files and scene loading live in the library (`lib.rs`) so that tests can use
//! them. Errors, usage errors included, end the process with one `lumis: …` line on stderr.

mod bench_cmd;
mod cli;
mod cpu_check;
mod export_cmd;
mod merge_cmd;
mod render_cmd;
mod view_cmd;

use clap::Parser;
use clap::error::ErrorKind;

fn main() {
    if let Some(e) = cpu_check::check() {
        eprintln!("lumis: {e}");
        std::process::exit(1);
    }
    let args = match cli::Cli::try_parse() {
        Ok(args) => args,
        // --help and --version (stdout, exit 0), and a bare `lumis` (help on stderr, exit 2).
        Err(e)
            if !e.use_stderr()
                || e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand =>
        {
            e.exit()
        }
        // Usage errors follow the one-line `lumis: ` convention too (clap's own text is several lines).
        Err(e) => {
            eprintln!("lumis: {}", one_line(&e.to_string()));
            std::process::exit(e.exit_code());
        }
    };
    let result = match args.command {
        cli::Command::Render(a) => render_cmd::render(&a),
        cli::Command::Compare(a) => render_cmd::compare(&a),
        cli::Command::Bench(a) => bench_cmd::bench(&a),
        cli::Command::View(a) => view_cmd::view(&a),
        cli::Command::Merge(a) => merge_cmd::merge(&a),
        cli::Command::Export(a) => export_cmd::export(&a),
    };
    if let Err(e) = result {
        eprintln!("lumis: {e:#}");
        std::process::exit(1);
    }
}

/// clap's multi-line error text as one line, without its usage and `--help` hints.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with("Usage:") && !l.starts_with("For more information")
        })
        .map(|l| l.strip_prefix("error: ").unwrap_or(l))
        .collect::<Vec<_>>()
        .join(" ")
}
