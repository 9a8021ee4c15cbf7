//! `lsys studio [PATH] [--port N] [--bind ADDR] [--open]`: the command line
//! -> a running [`crate::studio`] server, its URL printed, until Ctrl-C.

use std::net::IpAddr;
use std::path::PathBuf;

use clap::Args;

use super::{EX_IOERR, EX_OK};

#[derive(Args, Debug)]
pub struct StudioArgs {
    /// A grammar (.lsys), a Pailou component graph (.toml) or a folder; without it, the current folder and the default entrance.
    pub path: Option<PathBuf>,
    /// The port to listen on (0: a free one).
    #[arg(long, default_value_t = 8737)]
    pub port: u16,
    /// The address to listen on. Loopback unless you say otherwise: anyone who reaches the port can edit files in the opened folder.
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: IpAddr,
    /// Open the page in the default browser.
    #[arg(long)]
    pub open: bool,
    /// The built front end (default: web/studio/dist beside lsys's sources; see docs/studio.md).
    #[arg(long, value_name = "DIR")]
    pub assets: Option<PathBuf>,
    /// Triangles a model may have (instances counted in full); a larger one is refused with a message on the page.
    #[arg(long, value_name = "N", default_value_t = crate::studio::DEFAULT_MAX_TRIANGLES)]
    pub max_triangles: usize,
}

pub fn studio_cmd(a: &StudioArgs) -> i32 {
    let handle = match crate::studio::start(crate::studio::Config {
        path: a.path.clone(),
        bind: a.bind,
        port: a.port,
        assets: a.assets.clone(),
        max_triangles: Some(a.max_triangles),
    }) {
        Ok(h) => h,
        Err(e) => {
            eprintln!("lsys: studio: {e}");
            return EX_IOERR;
        }
    };
    let url = handle.url();
    if !a.bind.is_loopback() {
        eprintln!("lsys: warning: studio listens on {}: anyone who reaches it can read and write the opened folder", a.bind);
    }
    if a.assets.is_none()
        && !crate::studio::default_assets().join("index.html").is_file()
        && !crate::studio::has_embedded_page()
    {
        eprintln!("lsys: studio: the front end is not built; the page says how (cd web/studio && npm ci && npm run build)");
    }
    println!("lsys studio: {url}  (Ctrl-C stops)");
    if a.open {
        let opener = if cfg!(target_os = "macos") {
            "open"
        } else {
            "xdg-open"
        };
        if std::process::Command::new(opener)
            .arg(&url)
            .spawn()
            .is_err()
        {
            eprintln!("lsys: studio: cannot start {opener}; open {url} yourself");
        }
    }
    handle.wait();
    EX_OK
}
