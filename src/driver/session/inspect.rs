//! The commands that look at the session without changing the grammar:
//! `:show`, `:count`, `:diff`, `:rules`, `:defines`, `:disasm`, `:stats`,
//! and `:export` / `:render`, which build the current string through the
//! same code as `lsys build` ([`crate::build::build_string`],
//! [`crate::export::output::write_scene`]). Input: the session and the
//! argument text; output: the text to print.

use std::fmt::Write;
use std::path::Path;

use super::edit::rule;
use super::{show, Out, Session};
use crate::build::{self, BuildOptions, Built};
use crate::bytecode::{disasm, disasm_production, one_line};
use crate::derive::ModuleStore;
use crate::export::output::{write_scene, Format, WriteError};
use crate::export::render::{RenderOptions, View};
use crate::mesh::ComponentSearch;
use crate::resolve::Table;

impl Session {
    fn string(&self) -> Result<&ModuleStore, String> {
        self.grammar()?;
        self.current()
            .ok_or_else(|| "there is no string: the axiom could not be evaluated".to_string())
    }

    /// `:show [RANGE]`.
    pub fn show(&mut self, arg: &str) -> Out {
        let s = self.string()?;
        let program = &self.grammar()?.comp.program;
        let (symbols, fmt) = (&program.symbols, self.numbers(program));
        let n = s.len();
        let arg = arg.trim();
        if arg.is_empty() {
            return Ok(self.status());
        }
        if arg == "all" {
            return Ok(show::modules(s, symbols, fmt, 0..n));
        }
        let num = |t: &str, default: usize| -> Result<usize, String> {
            if t.trim().is_empty() {
                Ok(default)
            } else {
                t.trim()
                    .parse()
                    .map_err(|_| format!("`{arg}` is not a range: write A..B, A.., ..B, A or all"))
            }
        };
        let (a, b) = match arg.split_once("..") {
            Some((a, b)) => (num(a, 0)?, num(b, n)?),
            None => {
                let a = num(arg, 0)?;
                (a, a + 1)
            }
        };
        let (a, b) = (a.min(n), b.min(n));
        if a >= b {
            return Err(format!(
                "modules {arg}: nothing there (the string has {n} modules)"
            ));
        }
        Ok(format!(
            "modules {a}..{b} of {n}:\n{}",
            show::modules(s, symbols, fmt, a..b)
        ))
    }

    /// `:count`.
    pub fn count(&mut self) -> Out {
        let s = self.string()?;
        Ok(show::count_table(s, &self.grammar()?.comp.program.symbols))
    }

    /// `:diff`: step N-1 against step N.
    pub fn diff(&mut self) -> Out {
        self.string()?;
        if self.pos == 0 {
            return Err("step 0 is the axiom: there is no step before it to compare with".into());
        }
        let prev = self.string_at(self.pos - 1)?;
        let cur = self.string()?;
        let p = &self.grammar()?.comp.program;
        // Symbols a production (or the decomposition) can rewrite.
        let mut rewritable = vec![false; p.symbols.len()];
        for prod in p.productions.iter().chain(&p.decomposition) {
            for m in &prod.pred {
                rewritable[m.sym as usize] = true;
            }
        }
        Ok(show::diff(
            &prev,
            cur,
            &p.symbols,
            self.numbers(p),
            &rewritable,
            self.pos,
        ))
    }

    /// `:rules`.
    pub fn rules(&mut self) -> Out {
        let g = self.grammar()?;
        let p = &g.comp.program;
        let mut out = String::new();
        let mut n = 0;
        for (table, title) in [
            (Table::Main, "productions"),
            (Table::Decomposition, "decomposition"),
            (Table::Homomorphism, "homomorphism"),
        ] {
            let prods = p.table(table);
            if prods.is_empty() {
                continue;
            }
            let _ = writeln!(out, "{title}");
            let first = n;
            for (j, prod) in prods.iter().enumerate() {
                n += 1;
                let text = one_line(p.sources.slice(prod.span));
                let mark = if self.typed.contains(&text) { '*' } else { ' ' };
                let _ = write!(out, "{n:>3}{mark} {text}");
                if let Some(i) = super::shadow::shadowed_by(prods, j) {
                    let _ = write!(
                        out,
                        "   (never applies: rule {} comes first)",
                        first + i + 1
                    );
                }
                out.push('\n');
            }
        }
        if n == 0 {
            out.push_str("no productions yet: type one, e.g. `A --> A B`");
        }
        Ok(out.trim_end().to_string())
    }

    /// `:defines`.
    pub fn defines(&mut self) -> Out {
        let g = self.grammar()?;
        let p = &g.comp.program;
        if p.defines.is_empty() {
            return Ok("the grammar has no #define".into());
        }
        let w = p
            .defines
            .iter()
            .map(|d| d.name.chars().count())
            .max()
            .unwrap_or(0);
        let mut out = String::new();
        for d in &p.defines {
            let value = match d.value {
                Some(v) => v.to_string(),
                None => one_line(p.sources.slice(d.span)),
            };
            let pad = w - d.name.chars().count();
            let set = if d.overridden { "  (set)" } else { "" };
            let _ = writeln!(out, "{}{} = {value}{set}", d.name, " ".repeat(pad));
        }
        Ok(out.trim_end().to_string())
    }

    /// `:disasm [RULE]`.
    pub fn disasm(&mut self, arg: &str) -> Out {
        let g = self.grammar()?;
        let (p, c) = (&g.comp.program, &g.comp.compiled);
        if arg.is_empty() {
            return Ok(renumber(&disasm(p, c), 1));
        }
        let n: usize = arg
            .parse()
            .map_err(|_| format!("`:disasm` takes a rule number, not `{arg}`"))?;
        let prod = rule(&g.comp, n)?;
        let (table, index) = [Table::Main, Table::Decomposition, Table::Homomorphism]
            .into_iter()
            .find_map(|t| {
                p.table(t)
                    .iter()
                    .position(|q| std::ptr::eq(q, prod))
                    .map(|i| (t, i))
            })
            .expect("the rule is in one of the tables");
        let text = disasm_production(p, c, table, index).expect("the rule exists");
        Ok(renumber(&text, n))
    }

    /// The model the current string builds.
    fn model(&self) -> Result<Built, String> {
        let g = self.grammar()?;
        let s = self.string()?;
        let opts = BuildOptions {
            // The session's `-D` overrides: namespaced ones (`TM.NTL=3`)
            // reach the grammar components the model places.
            source: crate::load::Options {
                defines: self.overrides.clone(),
                ..Default::default()
            },
            derive: self.opts.clone(),
            components: ComponentSearch {
                grammar_dir: g.source.dir(),
                dirs: Vec::new(),
                ..Default::default()
            },
            ..Default::default()
        };
        let progress = super::meter(&self.meters);
        build::build_string(&g.comp, s, self.pos, &opts, &mut |st| progress.stage(st))
            .map_err(|e| crate::driver::render_diagnostic(&e, self.color))
    }

    /// `:stats`.
    pub fn stats(&mut self) -> Out {
        let g = self.grammar()?;
        let s = self.string()?;
        let p = &g.comp.program;
        let (kept, bytes) = self.history_size();
        let mut out = format!(
            "step {}: {} modules, {} parameter values, {} of {} symbols in use\n\
             grammar: {} ({} rules), seed {}, last derivation {:.1} ms\n\
             history: {kept} steps kept, {} KiB",
            self.pos,
            s.len(),
            s.param_count(),
            show::counts(s, &p.symbols).len(),
            p.symbols.len(),
            g.source.name(),
            p.productions.len() + p.decomposition.len() + p.homomorphism.len(),
            self.opts.effective_seed(p),
            self.derive_time.as_secs_f64() * 1e3,
            bytes.div_ceil(1024),
        );
        let built = self.model()?;
        let sc = &built.scene;
        let _ = write!(
            out,
            "\nmodel: {} triangles, {} vertices, {} component instances",
            sc.triangle_count(),
            sc.vertex_count(),
            sc.instance_counts().values().sum::<usize>(),
        );
        if let Some((lo, hi)) = sc.bounds() {
            let r = |v: glam::Vec3| format!("({:.3}, {:.3}, {:.3})", v.x, v.y, v.z);
            let _ = write!(out, ", bounds {} to {}", r(lo), r(hi));
        }
        let t = &built.timings;
        let _ = write!(
            out,
            "\nbuild: homomorphism {:.1} ms, turtle {:.1} ms, mesh {:.1} ms",
            t.derive.as_secs_f64() * 1e3,
            t.interpret.as_secs_f64() * 1e3,
            t.mesh.as_secs_f64() * 1e3
        );
        for w in &built.warnings {
            out.push('\n');
            out.push_str(crate::driver::render_diagnostic(w, self.color).trim_end());
        }
        Ok(out)
    }

    /// `:export FILE` and `:render FILE.png [VIEW]`.
    pub fn export(&mut self, arg: &str, picture: bool) -> Out {
        let mut words = arg.split_whitespace();
        let Some(path) = words.next() else {
            return Err(if picture {
                "`:render` needs a file: `:render FILE.png [VIEW]`".into()
            } else {
                "`:export` needs a file: FILE.glb, .gltf, .obj or .png".into()
            });
        };
        let path = Path::new(path);
        let format = match Format::of(path) {
            Some(Format::Png) => Format::Png,
            Some(_) if picture => {
                return Err("`:render` writes PNG pictures: name it FILE.png".into())
            }
            Some(f) => f,
            None => {
                return Err(format!(
                    "cannot tell the format of `{}`: name it .glb, .gltf, .obj or .png",
                    path.display()
                ))
            }
        };
        let view = match words.next() {
            Some(v) => v
                .parse::<View>()
                .map_err(|e| crate::driver::render_diagnostic(&e, self.color))?,
            None => View::Iso,
        };
        if let Some(extra) = words.next() {
            return Err(format!("unexpected `{extra}`"));
        }
        // The grammar and its includes are the session's inputs: never
        // overwritten by its own model.
        let sources = self.grammar()?.comp.program.sources.disk_paths();
        if let Err(e) = crate::export::atomic::refuse_inputs(path, &sources) {
            return Err(crate::driver::render_diagnostic(&e, self.color));
        }
        let built = self.model()?;
        let opts = RenderOptions {
            view,
            ..Default::default()
        };
        let progress = super::meter(&self.meters);
        progress.message(if format == Format::Png {
            "rendering"
        } else {
            "writing"
        });
        let written = write_scene(&built.scene, path, format, &opts);
        drop(progress);
        let bytes = written.map_err(|e| match e {
            WriteError::Export(d) => crate::driver::render_diagnostic(d.as_ref(), self.color),
            WriteError::Io(e) => format!("cannot write {}: {e}", path.display()),
        })?;
        let mut out = String::new();
        for w in &built.warnings {
            out.push_str(&crate::driver::render_diagnostic(w, self.color));
        }
        let _ = write!(
            out,
            "wrote {}: {bytes} bytes, {} triangles from {} modules",
            path.display(),
            built.scene.triangle_count(),
            built.modules
        );
        if built.scene.triangle_count() == 0 {
            out.push_str(" (the string draws nothing)");
        }
        Ok(out)
    }
}

/// The disassembler's `production I:` headers (numbered per table) as
/// `rule N:`, numbered from `first` as `:rules` numbers them.
fn renumber(listing: &str, first: usize) -> String {
    let mut n = first;
    let mut out = String::with_capacity(listing.len());
    for line in listing.trim_end().lines() {
        match line
            .strip_prefix("production ")
            .and_then(|r| r.split_once(": "))
        {
            Some((i, rest)) if i.chars().all(|c| c.is_ascii_digit()) => {
                out.push_str(&format!("rule {n}: {rest}"));
                n += 1;
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out.pop();
    out
}
