//! Running a guided scene: a [`Loaded`] scene in, an [`Outcome`] out (every
//! seed's final string and clipped drawing, the messages sent, the tokens
//! left). Each seed is its own [`Simulation`] with a [`GuidedQueries`]
//! environment; all seeds advance together, one pass per step:
//!
//! ```text
//! pass k = 0 .. steps-1:
//!     snapshot: every seed's string k drawn, placed and clipped -> elements per guide
//!     round 0: every seed, by guide then by its index in the guide:
//!              its queries answered on string k (tokens, messages), step k+1
//!     round r+1: the seeds the messages of round r created, same order:
//!              axiom = their string k, queries answered, step k+1
//!     tokens: reservations nobody targeted in this pass are freed
//! ```
//!
//! [`update`] re-derives one guide and the guides downstream of it, the
//! others replaying the messages they sent before.

use std::cell::RefCell;
use std::collections::BTreeSet;
use std::rc::Rc;

use super::draw;
use super::grid::ElementGrid;
use super::load::Loaded;
use super::queries::{Element, GuidedQueries, Message, Placement, World};
use super::tokens::LinkTokens;
use crate::derive::number::{NumberFormat, NumberStyle};
use crate::derive::{DeriveError, DeriveOptions};
use crate::simulation::{Environment, Simulation};
use crate::turtle::Drawing;

/// Where a seed came from.
#[derive(Clone, Debug, PartialEq)]
pub enum Origin {
    /// The scene's `[[seeds]]` entry.
    Explicit(usize),
    /// A message over this link, sent in this pass.
    Message { link: usize, pass: u32 },
}

/// One seed after the run.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedRun {
    pub guide: usize,
    /// Its index among the guide's seeds (explicit ones first).
    pub index: usize,
    pub origin: Origin,
    /// The pass whose step is its first.
    pub birth: u32,
    pub at: Placement,
    pub payload: Vec<f64>,
    pub grammar: usize,
    /// The final string, as `lsys derive --precision 4` prints it.
    pub string: String,
    /// Placed and clipped.
    pub drawing: Drawing,
}

/// A run's result.
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// By guide, then index in the guide.
    pub seeds: Vec<SeedRun>,
    /// In the order sent, each with the round it was sent in.
    pub messages: Vec<(Message, u32, usize)>,
    pub tokens: Vec<LinkTokens>,
}

impl Outcome {
    /// Every seed's string, one per line: `guide#index: string`.
    pub fn strings(&self, l: &Loaded) -> String {
        self.seeds
            .iter()
            .map(|s| {
                format!(
                    "{}#{} ({}): {}\n",
                    l.spec.guides[s.guide].name,
                    s.index,
                    match s.origin {
                        Origin::Explicit(_) => "explicit".to_string(),
                        Origin::Message { link, pass } =>
                            format!("link {} pass {pass}", l.spec.links[link].id),
                    },
                    s.string
                )
            })
            .collect()
    }

    /// All seeds' drawings in one.
    pub fn drawing(&self) -> Drawing {
        let mut d = Drawing::default();
        for s in &self.seeds {
            d.chains.extend(s.drawing.chains.iter().cloned());
            d.polygons.extend(s.drawing.polygons.iter().cloned());
            d.shapes.extend(s.drawing.shapes.iter().cloned());
            d.placements.extend(s.drawing.placements.iter().cloned());
        }
        d
    }
}

struct Live<'p> {
    run: SeedRun,
    /// Global ordinal (token holders).
    ordinal: usize,
    sim: Option<Simulation<'p>>,
}

/// The random seed of the `index`th seed of `guide`: the scene's seed,
/// the guide and the index mixed (SplitMix64's finaliser) so that every
/// bit of the result depends on all three. `ran` keeps only the low 32 bits
/// (drand48's seed, as cpfg's): the guide used to be mixed in above them,
/// so seed 0 of every guide drew the same random numbers.
fn derive_opts(l: &Loaded, guide: usize, index: usize) -> DeriveOptions {
    fn mix(mut z: u64) -> u64 {
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    let base = l.spec.seed.unwrap_or(0);
    let seed = mix(mix(mix(base) ^ guide as u64) ^ index as u64);
    DeriveOptions {
        seed: Some(seed & 0xffff_ffff),
        ..DeriveOptions::default()
    }
}

/// Runs the whole scene.
pub fn run(l: &Loaded) -> Result<Outcome, DeriveError> {
    execute(l, None)
}

/// Re-runs `changed` and every guide downstream of it; the other guides
/// keep `before`'s seeds and replay the messages they sent. Equal to
/// [`run`] on the changed scene.
pub fn update(l: &Loaded, before: &Outcome, changed: usize) -> Result<Outcome, DeriveError> {
    execute(l, Some((before, downstream(l, changed))))
}

/// `g` and every guide a chain of links from it reaches. A link without
/// tokens never sends a message (it only guides growth in its source), so
/// it reaches nothing.
pub fn downstream(l: &Loaded, g: usize) -> BTreeSet<usize> {
    let mut set = BTreeSet::from([g]);
    let mut todo = vec![g];
    while let Some(x) = todo.pop() {
        for link in l.spec.links.iter().filter(|k| k.from == x && k.tokens > 0) {
            if set.insert(link.to) {
                todo.push(link.to);
            }
        }
    }
    set
}

fn execute<'p>(
    l: &'p Loaded,
    frozen: Option<(&Outcome, BTreeSet<usize>)>,
) -> Result<Outcome, DeriveError> {
    let spec = &l.spec;
    let steps = spec.steps;
    let active = |g: usize| frozen.as_ref().map_or(true, |(_, set)| set.contains(&g));
    let world = Rc::new(RefCell::new(World {
        spec,
        tokens: spec
            .links
            .iter()
            .map(|k| LinkTokens::new(k.tokens))
            .collect(),
        elements: spec
            .guides
            .iter()
            .map(|_| ElementGrid::new(Vec::new()))
            .collect(),
        tags: vec![Vec::new(); spec.guides.len()],
        pass: 0,
        sent: Vec::new(),
    }));
    let mut live: Vec<Live<'p>> = Vec::new();
    let mut per_guide = vec![0usize; spec.guides.len()];
    let mut messages: Vec<(Message, u32, usize)> = Vec::new();
    let new_seed = |live: &mut Vec<Live<'p>>,
                    per_guide: &mut Vec<usize>,
                    guide: usize,
                    origin: Origin,
                    at: Placement,
                    payload: Vec<f64>,
                    grammar: usize,
                    birth: u32|
     -> Result<(), DeriveError> {
        let index = per_guide[guide];
        per_guide[guide] += 1;
        let ordinal = live.len();
        let sim = if active(guide) {
            let comp = &l.grammars[grammar];
            let env: Box<dyn Environment + 'p> = Box::new(GuidedQueries {
                world: Rc::clone(&world),
                seed: ordinal,
                guide,
                at,
                payload: payload.clone(),
            });
            Some(Simulation::with_environments(
                &comp.program,
                &comp.compiled,
                derive_opts(l, guide, index),
                steps - birth,
                vec![env],
            )?)
        } else {
            None
        };
        live.push(Live {
            run: SeedRun {
                guide,
                index,
                origin,
                birth,
                at,
                payload,
                grammar,
                string: String::new(),
                drawing: Drawing::default(),
            },
            ordinal,
            sim,
        });
        Ok(())
    };
    for (i, s) in spec.seeds.iter().enumerate() {
        let at = Placement {
            origin: s.position,
            heading: s.heading,
        };
        new_seed(
            &mut live,
            &mut per_guide,
            s.guide,
            Origin::Explicit(i),
            at,
            s.parameters.clone(),
            l.seed_grammar[i],
            0,
        )?;
    }
    for pass in 0..steps {
        // The snapshot every query of this pass reads.
        let mut elements = vec![Vec::new(); spec.guides.len()];
        for s in &live {
            if let Some(sim) = &s.sim {
                let d = placed(l, &s.run, sim)?;
                elements[s.run.guide].extend(draw::elements(&d, s.ordinal));
            }
        }
        {
            let mut w = world.borrow_mut();
            w.elements = elements.into_iter().map(ElementGrid::new).collect();
            w.pass = pass;
        }
        let mut round_seeds: Vec<usize> = (0..live.len()).collect();
        let mut round = 0;
        while !round_seeds.is_empty() {
            round_seeds.sort_by_key(|&i| (live[i].run.guide, live[i].run.index));
            let mut sent = Vec::new();
            let mut turn_of_guide: Option<usize> = None;
            for &i in &round_seeds {
                let g = live[i].run.guide;
                if let Some(sim) = &mut live[i].sim {
                    sim.step()?;
                    sent.extend(world.borrow_mut().sent.drain(..).map(|m| (m, round, g)));
                } else if turn_of_guide != Some(g) {
                    // A frozen guide sends what it sent before, at its turn.
                    let (before, _) = frozen.as_ref().expect("frozen seeds only when updating");
                    sent.extend(
                        before
                            .messages
                            .iter()
                            .filter(|(m, r, sg)| m.pass == pass && *r == round && *sg == g)
                            .cloned(),
                    );
                }
                turn_of_guide = Some(g);
            }
            let first = live.len();
            for (m, _, _) in &sent {
                let link = &spec.links[m.link];
                new_seed(
                    &mut live,
                    &mut per_guide,
                    link.to,
                    Origin::Message { link: m.link, pass },
                    m.at,
                    m.payload.clone(),
                    l.guide_grammar[link.to],
                    pass,
                )?;
            }
            messages.extend(sent);
            round_seeds = (first..live.len()).collect();
            round += 1;
        }
        for t in &mut world.borrow_mut().tokens {
            t.end_pass();
        }
    }
    let mut tokens = world.borrow().tokens.clone();
    let mut seeds = Vec::new();
    for mut s in live {
        if let Some(mut sim) = s.sim.take() {
            sim.finish()?;
            let comp = &l.grammars[s.run.grammar];
            s.run.drawing = placed(l, &s.run, &sim)?;
            s.run.string = sim.current().display_with(
                &comp.program.symbols,
                NumberFormat {
                    f32: false,
                    style: NumberStyle::Decimals(4),
                },
            );
            seeds.push(s.run);
        }
    }
    if let Some((before, set)) = &frozen {
        seeds.extend(
            before
                .seeds
                .iter()
                .filter(|s| !set.contains(&s.guide))
                .cloned(),
        );
        for (k, link) in spec.links.iter().enumerate() {
            if !set.contains(&link.from) {
                tokens[k] = before.tokens[k].clone();
            }
        }
    }
    seeds.sort_by_key(|s| (s.guide, s.index));
    Ok(Outcome {
        seeds,
        messages,
        tokens,
    })
}

/// A seed's current string drawn, placed and clipped to its guide.
fn placed(l: &Loaded, run: &SeedRun, sim: &Simulation<'_>) -> Result<Drawing, DeriveError> {
    let comp = &l.grammars[run.grammar];
    let local = draw::local_drawing(
        &comp.program,
        &comp.compiled,
        sim.current(),
        &derive_opts(l, run.guide, run.index),
        sim.step_number(),
    )
    .unwrap_or_default();
    Ok(draw::place_and_clip(
        &local,
        &run.at,
        &l.spec.guides[run.guide].points,
    ))
}

/// Every element of the outcome's guide `g` (tests).
pub fn guide_elements(o: &Outcome, g: usize) -> Vec<Element> {
    o.seeds
        .iter()
        .filter(|s| s.guide == g)
        .flat_map(|s| draw::elements(&s.drawing, s.index))
        .collect()
}
