//! `lumis`: the command line of the lumis path tracer.

mod cli;
mod render_cmd;

use clap::Parser;

fn main() {
    let args = cli::Cli::parse();
    let result = match args.command {
        cli::Command::Render(a) => render_cmd::render(&a),
        cli::Command::Compare(a) => render_cmd::compare(&a),
    };
    if let Err(e) = result {
        eprintln!("lumis: {e:#}");
        std::process::exit(1);
    }
}
