//! A cpfg model's view file: the model's `.l` path in, the functions of
//! its `function:` and `function set:` lines out (`func(id, x)` numbers
//! them from 1 in that order).
//!
//! cpfg is started with the view file on its command line; the model's
//! `specifications` file holds that line (`cpfg -M m.mat plant.l plant.v
//! plant.a`). Without it, the view file is the model's stem with `.v`.

use std::fs;
use std::path::{Path, PathBuf};

use crate::lang::spline::{parse_func, parse_gallery, SplineFn};

/// The view file cpfg would read for `model`, if there is one.
pub fn find_view_file(model: &Path) -> Option<PathBuf> {
    let dir = model.parent().unwrap_or(Path::new("."));
    if let Ok(spec) = fs::read_to_string(dir.join("specifications")) {
        for line in spec.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            if !words.iter().any(|w| *w == "cpfg" || w.ends_with("/cpfg")) {
                continue;
            }
            if let Some(v) = words.iter().find(|w| w.ends_with(".v")) {
                let p = dir.join(v);
                if p.is_file() {
                    return Some(p);
                }
            }
        }
    }
    let stem = model.with_extension("v");
    stem.is_file().then_some(stem)
}

/// The functions of the view file of `model`, in `func` order. `Ok(None)`
/// when there is no view file; `Err` names the file and line at fault.
pub fn load_functions(model: &Path) -> Result<Option<(PathBuf, Vec<SplineFn>)>, String> {
    let Some(view) = find_view_file(model) else {
        return Ok(None);
    };
    let dir = view.parent().unwrap_or(Path::new("."));
    let text = fs::read(&view).map_err(|e| format!("cannot read {}: {e}", view.display()))?;
    let text = String::from_utf8_lossy(&text);
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        let key = key.trim().to_ascii_lowercase();
        let gallery = match key.as_str() {
            "function" => false,
            "function set" | "functions" => true,
            _ => continue,
        };
        let Some(file) = rest.split_whitespace().next() else {
            return Err(format!(
                "{}:{}: `{key}:` names no file",
                view.display(),
                i + 1
            ));
        };
        let path = dir.join(file);
        let body = fs::read(&path).map_err(|e| {
            format!(
                "{}:{}: cannot read the function file {}: {e}",
                view.display(),
                i + 1,
                path.display()
            )
        })?;
        let body = String::from_utf8_lossy(&body);
        let parsed = if gallery {
            parse_gallery(&body)
        } else {
            let samples = rest
                .split_whitespace()
                .nth(1)
                .and_then(|n| n.parse().ok())
                .unwrap_or(0);
            parse_func(&body, samples).map(|f| vec![f])
        };
        match parsed {
            Ok(fs) => out.extend(fs),
            Err(e) => return Err(format!("{}:{}: {}", path.display(), e.line, e.message)),
        }
    }
    Ok(Some((view, out)))
}

/// The turning angle the view file gives (`angle factor: n` is 360/n
/// degrees, `angle increment: d` is d degrees), computed in `f32` as cpfg
/// reads it. `None` without a view file or either line.
pub fn view_angle(model: &Path) -> Option<f64> {
    let view = find_view_file(model)?;
    let text = fs::read(&view).ok()?;
    let text = String::from_utf8_lossy(&text);
    let mut angle = None;
    for line in text.lines() {
        let Some((key, rest)) = line.split_once(':') else {
            continue;
        };
        let value = rest
            .split_whitespace()
            .next()
            .and_then(|v| v.parse::<f32>().ok());
        match (key.trim().to_ascii_lowercase().as_str(), value) {
            ("angle factor", Some(n)) if n != 0.0 => angle = Some(f64::from(360.0f32 / n)),
            ("angle increment", Some(d)) => angle = Some(f64::from(d)),
            _ => {}
        }
    }
    angle
}
