//! The query modules of guided modeling (the paper's Table 2), answered
//! for one seed's string from the pass's [`World`]: the seed's string in,
//! its query parameters overwritten, tokens reserved and used, messages
//! recorded. One layout, outputs first, then inputs, then payload:
//!
//! ```text
//! ?DL ?DG ?DA (found, d, β, id_out, id_test)   closest link / guide / anything
//! ?NL ?NG ?NA (found, d, id_out, id_test)      first one straight ahead
//! ?X (found, id_out, ∆, id_in, id_test, payload…)  does P → P + ∆·H hit?
//! ```
//!
//! β is in degrees from the heading, + to the left. A module may stop
//! after any parameter; the missing ones read as 0. When nothing is found
//! only `found` is written (0).

use std::cell::RefCell;
use std::rc::Rc;

use glam::DVec2;

use super::geometry::{self, EPS};
pub use super::grid::Element;
use super::grid::ElementGrid;
use super::scene::{Continuity, SceneSpec};
use super::tokens::LinkTokens;
use crate::derive::{DeriveError, ModuleStore};
use crate::simulation::{Environment, StepContext};

/// A rigid motion of the drawing plane: where a seed's turtle starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub origin: DVec2,
    /// Degrees counter-clockwise from +x of the turtle's heading.
    pub heading: f64,
}

impl Placement {
    /// The turtle starts heading +y: turn by heading − 90°.
    fn rot(&self) -> DVec2 {
        geometry::direction(self.heading - 90.0)
    }

    pub fn vector(&self, v: DVec2) -> DVec2 {
        let r = self.rot();
        DVec2::new(r.x * v.x - r.y * v.y, r.y * v.x + r.x * v.y)
    }

    pub fn point(&self, p: DVec2) -> DVec2 {
        self.origin + self.vector(p)
    }
}

/// A message: `?X` of a seed touched the edge of a link with a token.
#[derive(Clone, Debug, PartialEq)]
pub struct Message {
    /// The pass (the step whose string was answered) that sent it.
    pub pass: u32,
    pub link: usize,
    pub from_seed: usize,
    /// Where the seed starts on the target edge, and its heading.
    pub at: Placement,
    /// `?X`'s parameters after id_test.
    pub payload: Vec<f64>,
}

/// What every seed's queries read and write during one pass.
pub struct World<'s> {
    pub spec: &'s SceneSpec,
    pub tokens: Vec<LinkTokens>,
    /// Per guide: the elements of every seed's string at this pass.
    pub elements: Vec<ElementGrid>,
    pub pass: u32,
    /// Messages of the pass, in the order sent.
    pub sent: Vec<Message>,
    /// Per guide: the segments `?X` asked about with a non-zero `id_in`,
    /// and that id. A drawn element that starts where one starts and ends
    /// on it answers with its id (see `World::element_id`).
    pub tags: Vec<Vec<(DVec2, DVec2, i64)>>,
}

impl World<'_> {
    /// The id an element of `guide` answers with: the latest tag whose
    /// segment it starts at and ends on, else 0.
    fn element_id(&self, guide: usize, e: &Element) -> i64 {
        self.tags[guide]
            .iter()
            .rev()
            .find(|(a, b, _)| {
                e.a.distance(*a) <= EPS
                    && geometry::closest_on_segment(e.b, *a, *b).0.distance(e.b) <= EPS
            })
            .map_or(0, |t| t.2)
    }
}

/// Which family a query module belongs to.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Distance(Target),
    Ahead(Target),
    Cross,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Links,
    Guide,
    Any,
}

fn kind_of(name: &str) -> Option<Kind> {
    Some(match name {
        "?DL" => Kind::Distance(Target::Links),
        "?DG" => Kind::Distance(Target::Guide),
        "?DA" => Kind::Distance(Target::Any),
        "?NL" => Kind::Ahead(Target::Links),
        "?NG" => Kind::Ahead(Target::Guide),
        "?NA" => Kind::Ahead(Target::Any),
        "?X" => Kind::Cross,
        _ => return None,
    })
}

/// One thing a query can find: a segment and the id it answers with.
struct Candidate {
    a: DVec2,
    b: DVec2,
    id: i64,
    /// The outgoing link whose edge this is.
    link: Option<usize>,
}

/// Answers one seed's guided queries (the seed's environment).
pub struct GuidedQueries<'s> {
    pub world: Rc<RefCell<World<'s>>>,
    /// The seed's run ordinal and guide.
    pub seed: usize,
    pub guide: usize,
    pub at: Placement,
    /// Written over the axiom's first module (explicit seeds' parameters,
    /// `?X` payloads).
    pub payload: Vec<f64>,
}

impl GuidedQueries<'_> {
    /// The guide and link edges a query of `kind` looks at, for this seed
    /// (the drawn elements are searched in the pass's grid).
    fn candidates(&self, w: &mut World<'_>, kind: Kind, id_test: i64) -> Vec<Candidate> {
        let spec = w.spec;
        let guide = &spec.guides[self.guide];
        let mut out = Vec::new();
        let target = match kind {
            Kind::Distance(t) | Kind::Ahead(t) => t,
            Kind::Cross => Target::Any,
        };
        for (k, (a, b)) in geometry::edges(&guide.points).enumerate() {
            let link = spec
                .links
                .iter()
                .position(|l| l.from == self.guide && l.from_edge == k);
            match link {
                Some(li) => {
                    let id = spec.links[li].id;
                    let named = id_test == id;
                    let sees = if kind == Kind::Cross {
                        true
                    } else if named {
                        w.tokens[li].target(self.seed)
                    } else {
                        w.tokens[li].visible()
                    };
                    if kind == Kind::Cross && named {
                        w.tokens[li].target(self.seed);
                    }
                    if target != Target::Guide && sees && (id_test == 0 || named) {
                        out.push(Candidate {
                            a,
                            b,
                            id,
                            link: Some(li),
                        });
                    } else if target != Target::Links && (id_test == 0 || id_test == guide.id) {
                        out.push(Candidate {
                            a,
                            b,
                            id: guide.id,
                            link: None,
                        });
                    }
                }
                None if target != Target::Links && (id_test == 0 || id_test == guide.id) => {
                    out.push(Candidate {
                        a,
                        b,
                        id: guide.id,
                        link: None,
                    });
                }
                None => {}
            }
        }
        out
    }

    fn answer(&self, w: &mut World<'_>, kind: Kind, p: DVec2, h: DVec2, args: &mut [f64]) {
        let get = |args: &[f64], k: usize| args.get(k).copied().unwrap_or(0.0);
        let set = |args: &mut [f64], k: usize, v: f64| {
            if let Some(x) = args.get_mut(k) {
                *x = v;
            }
        };
        let g = self.guide;
        // Drawn elements are found by ?DA, ?NA and ?X only.
        let elements = matches!(
            kind,
            Kind::Distance(Target::Any) | Kind::Ahead(Target::Any) | Kind::Cross
        );
        // Elements that start or end where the turtle stands are its own
        // last segment (or its sibling's start): never found.
        let own = |e: &Element| e.a.distance(p) <= EPS || e.b.distance(p) <= EPS;
        // An element's id costs a look through the tags: only when asked.
        let wanted = |w: &World<'_>, e: &Element, id_test: i64| {
            id_test == 0 || w.element_id(g, e) == id_test
        };
        // Guide and link edges come before elements: an element wins only
        // when strictly nearer, as in one scan of edges then elements.
        match kind {
            Kind::Distance(_) => {
                let id_test = get(args, 4) as i64;
                let edge = self
                    .candidates(w, kind, id_test)
                    .into_iter()
                    .map(|c| {
                        let (q, _) = geometry::closest_on_segment(p, c.a, c.b);
                        (p.distance(q), q, c.id)
                    })
                    .fold(None, |m: Option<(f64, DVec2, i64)>, x| match m {
                        Some(m) if m.0 <= x.0 => Some(m),
                        _ => Some(x),
                    });
                let found = if elements {
                    let w = &*w;
                    w.elements[g].nearest(p, |_, e| {
                        (!own(e) && wanted(w, e, id_test))
                            .then(|| geometry::distance_to_segment(p, e.a, e.b))
                    })
                } else {
                    None
                };
                let best = match found {
                    Some((d, k)) if edge.map_or(true, |x| d < x.0) => {
                        let e = w.elements[g].elements()[k];
                        let (q, _) = geometry::closest_on_segment(p, e.a, e.b);
                        Some((d, q, w.element_id(g, &e)))
                    }
                    _ => edge,
                };
                match best {
                    Some((d, q, id)) => {
                        let beta = if d <= EPS {
                            0.0
                        } else {
                            geometry::signed_angle(h, q - p)
                        };
                        set(args, 0, 1.0);
                        set(args, 1, d);
                        set(args, 2, beta);
                        set(args, 3, id as f64);
                    }
                    None => set(args, 0, 0.0),
                }
            }
            Kind::Ahead(_) => {
                let id_test = get(args, 3) as i64;
                let edge = self
                    .candidates(w, kind, id_test)
                    .into_iter()
                    .filter_map(|c| geometry::ray_hit(p, h, c.a, c.b).map(|d| (d, c.id)))
                    .fold(None, |m: Option<(f64, i64)>, x| match m {
                        Some(m) if m.0 <= x.0 => Some(m),
                        _ => Some(x),
                    });
                let found = if elements {
                    let w = &*w;
                    w.elements[g].along(p, h, f64::INFINITY, |_, e| {
                        wanted(w, e, id_test)
                            .then(|| geometry::ray_hit(p, h, e.a, e.b))
                            .flatten()
                    })
                } else {
                    None
                };
                let best = match found {
                    Some((d, k)) if edge.map_or(true, |x| d < x.0) => {
                        Some((d, w.element_id(g, &w.elements[g].elements()[k])))
                    }
                    _ => edge,
                };
                match best {
                    Some((d, id)) => {
                        set(args, 0, 1.0);
                        set(args, 1, d);
                        set(args, 2, id as f64);
                    }
                    None => set(args, 0, 0.0),
                }
            }
            Kind::Cross => {
                let delta = get(args, 2);
                let id_in = get(args, 3) as i64;
                let id_test = get(args, 4) as i64;
                let q = p + h * delta;
                let len = delta.abs();
                // The element this `?X` asks about carries id_in once drawn.
                if id_in != 0 && len > EPS {
                    let tags = &mut w.tags[g];
                    if !tags
                        .iter()
                        .any(|t| t.0.distance(p) <= EPS && t.1.distance(q) <= EPS && t.2 == id_in)
                    {
                        tags.push((p, q, id_in));
                    }
                }
                // A hit must lie ahead of the turtle's own start.
                let hit = |a: DVec2, b: DVec2| {
                    let (t, u) = geometry::segment_hit(p, q, a, b)?;
                    (t * len > EPS).then_some((t * len, u))
                };
                let edge = self
                    .candidates(w, kind, id_test)
                    .into_iter()
                    .filter_map(|c| hit(c.a, c.b).map(|(d, u)| (d, u, c)))
                    .fold(None, |m: Option<(f64, f64, Candidate)>, x| match m {
                        Some(m) if m.0 <= x.0 => Some(m),
                        _ => Some(x),
                    });
                let found = if len > EPS {
                    let w = &*w;
                    w.elements[g].along(p, h * delta.signum(), len, |_, e| {
                        (!own(e) && wanted(w, e, id_test))
                            .then(|| hit(e.a, e.b).map(|(d, _)| d))
                            .flatten()
                    })
                } else {
                    None
                };
                let best = match found {
                    Some((d, k)) if edge.as_ref().map_or(true, |x| d < x.0) => {
                        let e = w.elements[g].elements()[k];
                        hit(e.a, e.b).map(|(d, u)| {
                            let c = Candidate {
                                a: e.a,
                                b: e.b,
                                id: w.element_id(g, &e),
                                link: None,
                            };
                            (d, u, c)
                        })
                    }
                    _ => edge,
                };
                let Some((_, u, c)) = best else {
                    set(args, 0, 0.0);
                    return;
                };
                set(args, 0, 1.0);
                set(args, 1, c.id as f64);
                if let Some(li) = c.link {
                    if w.tokens[li].use_token(self.seed) {
                        let link = &w.spec.links[li];
                        let target = &w.spec.guides[link.to];
                        let (ta, tb) = target.edge(link.to_edge);
                        // Facing edges: the same parameter from the other end,
                        // so that snapped guides meet at one point.
                        let origin = tb + (ta - tb) * u;
                        let heading = match link.continuity {
                            Continuity::C1 => h.y.atan2(h.x).to_degrees(),
                            Continuity::C0 => {
                                let n = target.inward_normal(link.to_edge);
                                n.y.atan2(n.x).to_degrees() + link.heading
                            }
                        };
                        let payload = args.get(5..).map_or(Vec::new(), <[f64]>::to_vec);
                        let pass = w.pass;
                        w.sent.push(Message {
                            pass,
                            link: li,
                            from_seed: self.seed,
                            at: Placement { origin, heading },
                            payload,
                        });
                    }
                }
            }
        }
    }
}

impl Environment for GuidedQueries<'_> {
    fn after_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        // The seed's parameters reach the axiom's first module.
        if ctx.step == 0 && !string.is_empty() && !self.payload.is_empty() {
            let n = crate::derive::store::head_arity(string.heads()[0]);
            let params = string.params_mut();
            for (k, v) in self.payload.iter().take(n).enumerate() {
                params[k] = *v;
            }
        }
        Ok(())
    }

    fn before_step(
        &mut self,
        ctx: &StepContext<'_>,
        string: &mut ModuleStore,
    ) -> Result<(), DeriveError> {
        let program = ctx.program;
        let kinds: Vec<Option<Kind>> = program
            .symbols
            .list
            .iter()
            .map(|s| kind_of(&s.name))
            .collect();
        if kinds.iter().all(Option::is_none) {
            return Ok(());
        }
        // Where the turtle draws each query: through the homomorphism.
        let Some(sites) = crate::simulation::drawn_sites(ctx, string) else {
            return Ok(());
        };
        let world = Rc::clone(&self.world);
        let mut w = world.borrow_mut();
        let params = string.params_mut();
        for s in sites {
            let Some(kind) = kinds[s.sym as usize] else {
                continue;
            };
            let p = self.at.point(DVec2::new(s.frame.pos.x, s.frame.pos.y));
            let h = self
                .at
                .vector(DVec2::new(s.frame.h.x, s.frame.h.y))
                .normalize_or(DVec2::Y);
            let args = &mut params[s.offset..s.offset + s.arity];
            self.answer(&mut w, kind, p, h, args);
        }
        Ok(())
    }
}
