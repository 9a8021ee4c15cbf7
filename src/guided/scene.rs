//! The scene file of guided procedural modeling: TOML text in, a checked
//! [`SceneSpec`] out (guides, links, explicit seeds), every mistake a
//! located diagnostic (`lsys::guided::*`). Grammars are only named here;
//! `load.rs` compiles them. The format is in docs/guided.md.

use std::collections::BTreeMap;
use std::ops::Range;

use glam::DVec2;
use miette::{Diagnostic, NamedSource, SourceSpan};
use serde::Deserialize;
use thiserror::Error;
use toml::Spanned;

use super::geometry;

/// A mistake in a scene file.
#[derive(Debug, Error, Diagnostic)]
pub enum SceneError {
    #[error("{file} is not a guided scene: {message}")]
    #[diagnostic(
        code(lsys::guided::syntax),
        help("a scene has `steps`, [[guide]] tables (name, grammar, points), [[link]] and [[seed]] tables; see docs/guided.md")
    )]
    Syntax {
        file: String,
        message: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("here")]
        span: Option<SourceSpan>,
    },

    #[error("{message}")]
    #[diagnostic(code(lsys::guided::scene))]
    Scene {
        message: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("{label}")]
        span: SourceSpan,
        label: String,
        #[help]
        help: String,
    },

    #[error("the grammar `{grammar}` is outside the scene's folder")]
    #[diagnostic(code(lsys::guided::outside))]
    Outside {
        grammar: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("not read: outside the allowed folders")]
        span: SourceSpan,
        /// The folders allowed, and how to allow another.
        #[help]
        help: String,
    },

    #[error("the grammar `{grammar}` does not compile")]
    #[diagnostic(code(lsys::guided::grammar))]
    Grammar {
        grammar: String,
        #[source_code]
        src: NamedSource<crate::source::SourceText>,
        #[label("this grammar")]
        span: SourceSpan,
        /// The grammar's own diagnostics, rendered.
        #[help]
        details: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    steps: Spanned<u32>,
    seed: Option<u64>,
    #[serde(default)]
    guide: Vec<GuideFile>,
    #[serde(default)]
    link: Vec<LinkFile>,
    #[serde(default)]
    seeds: Vec<SeedFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GuideFile {
    name: Spanned<String>,
    grammar: Spanned<String>,
    points: Spanned<Vec<[f64; 2]>>,
    height: Option<f64>,
    id: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LinkFile {
    from: Spanned<String>,
    from_edge: Spanned<usize>,
    to: Spanned<String>,
    to_edge: Spanned<usize>,
    #[serde(default)]
    tokens: u32,
    continuity: Spanned<String>,
    #[serde(default)]
    heading: f64,
    id: Option<Spanned<i64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SeedFile {
    guide: Spanned<String>,
    position: Spanned<[f64; 2]>,
    heading: f64,
    grammar: Option<Spanned<String>>,
    #[serde(default)]
    parameters: Vec<f64>,
}

/// How a message's seed is headed (Fig 3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Continuity {
    /// Only the point carries over; the heading is the link's own.
    C0,
    /// The heading of the module that touched the edge continues.
    C1,
}

/// A closed polygon hosting a grammar.
#[derive(Clone, Debug, PartialEq)]
pub struct Guide {
    pub name: String,
    /// `path` (relative to the scene file) or `std:NAME`.
    pub grammar: String,
    pub grammar_span: Range<usize>,
    /// As the file lists them (either orientation).
    pub points: Vec<DVec2>,
    /// Extrusion height of the overlay prism (0: flat).
    pub height: f64,
    pub id: i64,
}

impl Guide {
    /// Edge `k`: from vertex `k` to vertex `k + 1`, as the file numbers it.
    pub fn edge(&self, k: usize) -> (DVec2, DVec2) {
        (self.points[k], self.points[(k + 1) % self.points.len()])
    }

    /// The unit normal of edge `k` pointing into the guide.
    pub fn inward_normal(&self, k: usize) -> DVec2 {
        let (a, b) = self.edge(k);
        let d = (b - a).normalize_or_zero();
        let left = DVec2::new(-d.y, d.x);
        if geometry::signed_area2(&self.points) > 0.0 {
            left
        } else {
            -left
        }
    }
}

/// An oriented link from an edge of one guide to an edge of another.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    pub from: usize,
    pub from_edge: usize,
    pub to: usize,
    pub to_edge: usize,
    pub tokens: u32,
    pub continuity: Continuity,
    /// C0: the seed's heading in degrees from the target edge's inward
    /// normal, + to the left.
    pub heading: f64,
    pub id: i64,
}

/// A seed the user placed.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedSpec {
    pub guide: usize,
    pub position: DVec2,
    /// Degrees counter-clockwise from +x (90: the turtle's own +y).
    pub heading: f64,
    /// Another grammar than the guide's.
    pub grammar: Option<(String, Range<usize>)>,
    /// Written over the parameters of the axiom's first module.
    pub parameters: Vec<f64>,
}

/// A checked scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneSpec {
    pub steps: u32,
    pub seed: Option<u64>,
    pub guides: Vec<Guide>,
    pub links: Vec<Link>,
    pub seeds: Vec<SeedSpec>,
}

struct Reader {
    src: NamedSource<crate::source::SourceText>,
}

impl Reader {
    fn err(
        &self,
        span: Range<usize>,
        message: String,
        label: &str,
        help: String,
    ) -> Box<SceneError> {
        Box::new(SceneError::Scene {
            message,
            src: self.src.clone(),
            span: span.into(),
            label: label.to_string(),
            help,
        })
    }
}

/// Reads a scene file (`name` for messages).
pub fn read(name: &str, text: &str) -> Result<SceneSpec, Box<SceneError>> {
    let src = NamedSource::new(name, crate::source::SourceText::from(text.to_string()));
    let file: File = toml::from_str(text).map_err(|e| {
        Box::new(SceneError::Syntax {
            file: name.to_string(),
            message: e.message().to_string(),
            src: src.clone(),
            span: e.span().map(Into::into),
        })
    })?;
    let r = Reader { src };
    let mut by_name: BTreeMap<String, usize> = BTreeMap::new();
    let mut ids: BTreeMap<i64, Range<usize>> = BTreeMap::new();
    let mut guides = Vec::new();
    // Default ids count up from 1 over guides, then links, skipping the
    // ids the file gives explicitly.
    let explicit: std::collections::BTreeSet<i64> = file
        .guide
        .iter()
        .filter_map(|g| g.id.as_ref().map(|i| *i.get_ref()))
        .chain(
            file.link
                .iter()
                .filter_map(|l| l.id.as_ref().map(|i| *i.get_ref())),
        )
        .collect();
    let mut next_id = 0i64;
    let mut fresh = || loop {
        next_id += 1;
        if !explicit.contains(&next_id) {
            return next_id;
        }
    };
    for (k, g) in file.guide.iter().enumerate() {
        let gname = g.name.get_ref().clone();
        if by_name.insert(gname.clone(), k).is_some() {
            return Err(r.err(
                g.name.span(),
                format!("two guides are named `{gname}`"),
                "the second one",
                "give every guide its own name: links and seeds name them".into(),
            ));
        }
        let points: Vec<DVec2> = g.points.get_ref().iter().map(|p| DVec2::from(*p)).collect();
        if points.len() < 3 || points.iter().any(|p| !p.is_finite()) {
            return Err(r.err(
                g.points.span(),
                format!("the guide `{gname}` needs at least 3 finite points"),
                "these points",
                "a guide is a closed polygon: `points = [[0, 0], [4, 0], [4, 4], [0, 4]]`".into(),
            ));
        }
        let area = geometry::signed_area2(&points);
        if area.abs() <= geometry::EPS {
            return Err(r.err(
                g.points.span(),
                format!("the guide `{gname}` has no area"),
                "these points",
                "its points all lie on one line".into(),
            ));
        }
        let (id, id_span) = match &g.id {
            Some(i) => (*i.get_ref(), i.span()),
            None => (fresh(), g.name.span()),
        };
        guides.push(Guide {
            name: gname,
            grammar: g.grammar.get_ref().clone(),
            grammar_span: g.grammar.span(),
            points,
            height: g.height.unwrap_or(0.0),
            id,
        });
        check_id(&r, &mut ids, id, id_span)?;
    }
    let guide = |s: &Spanned<String>| {
        by_name.get(s.get_ref()).copied().ok_or_else(|| {
            r.err(
                s.span(),
                format!("no guide is named `{}`", s.get_ref()),
                "this guide",
                format!(
                    "the guides are: {}",
                    by_name.keys().cloned().collect::<Vec<_>>().join(", ")
                ),
            )
        })
    };
    let mut links = Vec::new();
    for l in &file.link {
        let from = guide(&l.from)?;
        let to = guide(&l.to)?;
        for (g, e) in [(from, &l.from_edge), (to, &l.to_edge)] {
            let n = guides[g].points.len();
            if *e.get_ref() >= n {
                return Err(r.err(
                    e.span(),
                    format!(
                        "the guide `{}` has {n} edges (0 to {}), not {}",
                        guides[g].name,
                        n - 1,
                        e.get_ref()
                    ),
                    "this edge",
                    "edge k joins point k to point k + 1 (the last edge closes the polygon)".into(),
                ));
            }
        }
        let continuity = match l.continuity.get_ref().to_ascii_uppercase().as_str() {
            "C0" => Continuity::C0,
            "C1" => Continuity::C1,
            other => {
                return Err(r.err(
                    l.continuity.span(),
                    format!("unknown continuity `{other}`"),
                    "this continuity",
                    "`C0` (the point only) or `C1` (the heading continues)".into(),
                ))
            }
        };
        let (id, id_span) = match &l.id {
            Some(i) => (*i.get_ref(), i.span()),
            None => (fresh(), l.from.span()),
        };
        check_id(&r, &mut ids, id, id_span)?;
        links.push(Link {
            from,
            from_edge: *l.from_edge.get_ref(),
            to,
            to_edge: *l.to_edge.get_ref(),
            tokens: l.tokens,
            continuity,
            heading: l.heading,
            id,
        });
    }
    let mut seeds = Vec::new();
    for s in &file.seeds {
        let g = guide(&s.guide)?;
        let position = DVec2::from(*s.position.get_ref());
        if !geometry::inside(position, &guides[g].points) {
            return Err(r.err(
                s.position.span(),
                format!("the seed lies outside its guide `{}`", guides[g].name),
                "this position",
                "a seed starts inside its guide or on its boundary".into(),
            ));
        }
        seeds.push(SeedSpec {
            guide: g,
            position,
            heading: s.heading,
            grammar: s.grammar.as_ref().map(|g| (g.get_ref().clone(), g.span())),
            parameters: s.parameters.clone(),
        });
    }
    if *file.steps.get_ref() > 100_000 {
        return Err(r.err(
            file.steps.span(),
            "more than 100000 steps".into(),
            "this count",
            "a guided scene derives every seed this many steps".into(),
        ));
    }
    Ok(SceneSpec {
        steps: *file.steps.get_ref(),
        seed: file.seed,
        guides,
        links,
        seeds,
    })
}

fn check_id(
    r: &Reader,
    ids: &mut BTreeMap<i64, Range<usize>>,
    id: i64,
    span: Range<usize>,
) -> Result<(), Box<SceneError>> {
    if id == 0 {
        return Err(r.err(
            span,
            "the id 0 means `any` in query modules".into(),
            "this id",
            "give guides and links ids other than 0".into(),
        ));
    }
    if ids.insert(id, span.clone()).is_some() {
        return Err(r.err(
            span,
            format!("the id {id} is used twice"),
            "the second use",
            "guides and links share one id space (defaults count up from 1, guides first, skipping explicit ids)".into(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        crate::diag::render_plain(read("t.toml", text).unwrap_err().as_ref())
    }

    const GUIDE: &str =
        "steps = 3\n[[guide]]\nname = \"a\"\ngrammar = \"std:x\"\npoints = [[0,0],[1,0],[1,1]]\n";

    #[test]
    fn a_good_scene_reads() {
        let s = read(
            "t.toml",
            &format!("{GUIDE}[[seeds]]\nguide = \"a\"\nposition = [0.5, 0.2]\nheading = 90\n"),
        )
        .unwrap();
        assert_eq!(s.guides[0].id, 1);
        assert_eq!(s.seeds[0].guide, 0);
    }

    #[test]
    fn mistakes_are_located() {
        let e = err(&format!("{GUIDE}[[link]]\nfrom = \"a\"\nfrom_edge = 5\nto = \"a\"\nto_edge = 0\ncontinuity = \"C1\"\n"));
        assert!(
            e.contains("lsys::guided::scene") && e.contains("has 3 edges"),
            "{e}"
        );
        let e = err(&format!("{GUIDE}[[link]]\nfrom = \"a\"\nfrom_edge = 0\nto = \"zz\"\nto_edge = 0\ncontinuity = \"C1\"\n"));
        assert!(e.contains("no guide is named `zz`"), "{e}");
        let e = err(&format!(
            "{GUIDE}[[seeds]]\nguide = \"a\"\nposition = [5, 5]\nheading = 0\n"
        ));
        assert!(e.contains("outside its guide"), "{e}");
        let e = err("steps = 1\n[[guide]]\nname = \"a\"\n");
        assert!(e.contains("lsys::guided::syntax"), "{e}");
        let e = err(&format!("{GUIDE}[[link]]\nfrom = \"a\"\nfrom_edge = 0\nto = \"a\"\nto_edge = 1\ncontinuity = \"G2\"\n"));
        assert!(e.contains("unknown continuity"), "{e}");
    }
}
