//! The `dieplan` command: `serve` runs the service; `openapi` prints its OpenAPI document;
//! `keys` makes, lists and revokes API keys.

use clap::{Parser, Subcommand};
use dieplan::service::app;
use dieplan::service::config::Config;
use dieplan::service::keys::cli::KeysCommand;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "dieplan",
    version,
    about = "Die and mold milling planner: overload analysis, trochoids, constant-force feeds, tool life and cost"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run the HTTP service.
    Serve(Config),
    /// Print the OpenAPI document (as committed in openapi/openapi.json).
    Openapi,
    /// Make, list and revoke API keys on the service's database.
    #[command(subcommand)]
    Keys(KeysCommand),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Openapi => {
            print!("{}", dieplan::service::openapi::document_json());
            ExitCode::SUCCESS
        }
        Command::Serve(config) => serve(config),
        Command::Keys(command) => keys(command),
    }
}

fn keys(command: KeysCommand) -> ExitCode {
    let runtime = match tokio::runtime::Builder::new_current_thread().enable_all().build() {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("dieplan: cannot start the async runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    match runtime.block_on(dieplan::service::keys::cli::run(command)) {
        Ok(out) => {
            println!("{out}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("dieplan: {e}");
            ExitCode::FAILURE
        }
    }
}

fn serve(config: Config) -> ExitCode {
    app::init_tracing(&config);
    let runtime = match tokio::runtime::Builder::new_multi_thread().enable_all().build() {
        Ok(rt) => rt,
        Err(e) => {
            eprintln!("dieplan: cannot start the async runtime: {e}");
            return ExitCode::FAILURE;
        }
    };
    let code = runtime.block_on(async move {
        match app::start(config).await {
            Ok(server) => {
                app::shutdown_signal().await;
                server.stop().await;
                ExitCode::SUCCESS
            }
            Err(e) => {
                tracing::error!(error = %e, "dieplan could not start");
                eprintln!("dieplan: {e}");
                ExitCode::FAILURE
            }
        }
    });
    // A job that did not stop within the grace period runs on a blocking thread; dropping
    // the runtime would wait for it. It resumes at the next start.
    runtime.shutdown_background();
    code
}
