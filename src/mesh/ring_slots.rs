//! Where tubes can share rings: a drawing's chains (and the turtle's
//! [`Origin`]s of them) -> a slot per distinct (colour, position, radius),
//! bit for bit, at which some chain starts, the first chain starting at
//! each, and the slot of every point of every chain (`NONE` where no chain
//! starts). [`super::tubes`] keeps one ring per slot.
//!
//! The answer is the one of looking every point up by its key. Origins
//! only save lookups: a chain whose first point has the same key as its
//! origin is in the same slot as the origin, so of all the points known to
//! be equal that way, one is looked up (a start), or none when no chain
//! starts there and a filter of the start keys says so. Each lookup in a
//! table of all starts waits for a cache miss; the lookups were most of
//! the meshing time.

use std::collections::HashMap;
use std::hash::BuildHasher;

use rustc_hash::FxBuildHasher;

use crate::turtle::drawing::{Chain, Origin, TubePoint};

/// No chain starts at this point.
pub(super) const NONE: u32 = u32::MAX;

/// Not known yet.
const UNSET: u32 = u32::MAX - 1;

/// Where rings can be shared: the colour, position and radius of a point,
/// bit for bit (the turtle writes a branch's first point from the same
/// value as its parent's).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
struct Key {
    colour: u32,
    x: u32,
    y: u32,
    z: u32,
    radius: u32,
}

fn key(colour: u32, p: &TubePoint) -> Key {
    Key {
        colour,
        x: p.pos.x.to_bits(),
        y: p.pos.y.to_bits(),
        z: p.pos.z.to_bits(),
        radius: p.radius.to_bits(),
    }
}

/// A one-hash Bloom filter of the start keys: 16 bits a start (about one
/// false "maybe" in 16), small enough to stay in cache where the table of
/// starts is not.
struct Filter {
    words: Vec<u64>,
    shift: u32,
}

impl Filter {
    fn new(starts: usize) -> Filter {
        let bits = (starts.max(4) * 16).next_power_of_two();
        Filter {
            words: vec![0; bits / 64],
            shift: 64 - bits.trailing_zeros(),
        }
    }

    fn bit(&self, k: &Key) -> (usize, u64) {
        // The top bits: FxHash's finish rotates multiplied (mixed) bits there.
        let b = (FxBuildHasher.hash_one(k) >> self.shift) as usize;
        (b / 64, 1 << (b % 64))
    }

    fn insert(&mut self, k: &Key) {
        let (w, m) = self.bit(k);
        self.words[w] |= m;
    }

    fn may_hold(&self, k: &Key) -> bool {
        let (w, m) = self.bit(k);
        self.words[w] & m != 0
    }
}

/// The slots of a drawing's chains.
pub(super) struct Slots {
    /// Per slot, the first chain (in order) that starts there.
    pub first_chain: Vec<usize>,
    /// The slot of every point of every chain (`NONE` where no chain
    /// starts), chain after chain.
    pub point_slots: Vec<u32>,
    /// Where each chain's points begin in `point_slots`, and their end.
    pub first_point: Vec<usize>,
}

/// The slots of `chains`; `origins` (per chain, maybe shorter) are
/// checked before use, so wrong ones only cost lookups.
pub(super) fn slots(chains: &[Chain], origins: &[Option<Origin>]) -> Slots {
    let total = chains.iter().map(|c| c.points.len()).sum();
    let mut first_point = Vec::with_capacity(chains.len() + 1);
    // Per chain, the earliest point known to have its first point's key:
    // that point's own number, or its origin's root.
    let mut root: Vec<u32> = Vec::with_capacity(chains.len());
    // Per point, its slot; at a root, the slot of its key once known (a
    // root comes before the points that refer to it).
    let mut point_slots = vec![UNSET; total];
    let mut table: HashMap<Key, u32, FxBuildHasher> = HashMap::default();
    let mut filter = Filter::new(chains.len());
    let mut first_chain = Vec::new();
    // One pass for the roots and the starts: each pass over the chains
    // reads every chain's points from its own allocation.
    let mut from = 0;
    for (j, c) in chains.iter().enumerate() {
        first_point.push(from);
        root.push(from as u32);
        from += c.points.len();
        let Some(first) = c.points.first().filter(|_| c.points.len() >= 2) else {
            continue;
        };
        if let Some(Some(o)) = origins.get(j) {
            let (oc, ok) = (o.chain as usize, o.point as usize);
            let p = chains[..j]
                .get(oc)
                .and_then(|o| o.points.get(ok).map(|p| (o, p)));
            if let Some((o, p)) = p {
                if key(o.colour, p) == key(c.colour, first) {
                    root[j] = if ok == 0 {
                        root[oc]
                    } else {
                        (first_point[oc] + ok) as u32
                    };
                }
            }
        }
        let r = root[j] as usize;
        if point_slots[r] == UNSET {
            let k = key(c.colour, first);
            point_slots[r] = *table.entry(k).or_insert_with(|| {
                filter.insert(&k);
                first_chain.push(j);
                (first_chain.len() - 1) as u32
            });
        }
    }
    first_point.push(from);
    for (j, c) in chains.iter().enumerate() {
        let from = first_point[j];
        for (i, p) in c.points.iter().enumerate() {
            let r = if i == 0 { root[j] as usize } else { from + i };
            if point_slots[r] == UNSET {
                let k = key(c.colour, p);
                point_slots[r] = if filter.may_hold(&k) {
                    table.get(&k).copied().unwrap_or(NONE)
                } else {
                    NONE
                };
            }
            point_slots[from + i] = point_slots[r];
        }
    }
    Slots {
        first_chain,
        point_slots,
        first_point,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::tube::tests::chain;
    use glam::Vec3;

    /// The slots by looking every point up, as before origins.
    fn looked_up(chains: &[Chain]) -> (Vec<usize>, Vec<u32>) {
        let mut table = HashMap::new();
        let mut first_chain = Vec::new();
        for (j, c) in chains.iter().enumerate() {
            if c.points.len() >= 2 {
                table.entry(key(c.colour, &c.points[0])).or_insert_with(|| {
                    first_chain.push(j);
                    (first_chain.len() - 1) as u32
                });
            }
        }
        let points = chains.iter().flat_map(|c| {
            let table = &table;
            c.points
                .iter()
                .map(move |p| table.get(&key(c.colour, p)).copied().unwrap_or(NONE))
        });
        (first_chain, points.collect())
    }

    /// Origins right, wrong, missing or pointing nowhere, and points that
    /// meet by position only, give the slots of looking every point up.
    #[test]
    fn origins_only_save_lookups() {
        let (o, y, x) = (Vec3::ZERO, Vec3::Y, Vec3::X);
        let mut chains = vec![
            chain(&[o, y], 0.1),
            chain(&[y, y + x], 0.1),
            chain(&[y, y - x], 0.1),
            // meets the first chain's end by position only
            chain(&[x, y], 0.1),
            // starts where chain 1 ends, but narrower
            chain(&[y + x, y + 2.0 * x], 0.05),
            // a leaf whose end nothing starts from
            chain(&[y - x, 2.0 * y], 0.1),
            // starts at the end of chain 3 (= chain 0's end)
            chain(&[y, 3.0 * y], 0.1),
        ];
        chains.push(Chain {
            colour: 1,
            ..chain(&[y, x], 0.1)
        });
        // from the first point of chain 6, whose origin is chain 3's end
        chains.push(chain(&[y, 4.0 * y], 0.1));
        // a chain of one point, and one that refers to itself
        chains.push(chain(&[x], 0.1));
        chains.push(chain(&[2.0 * x, y], 0.1));
        let at = |chain, point| Some(Origin { chain, point });
        let origins = [
            None,
            at(0, 1),
            at(0, 1),
            None,
            at(1, 1), // radius differs: not the same key
            at(2, 1),
            at(3, 1),
            at(0, 1), // colour differs
            at(6, 0),
            at(3, 0),
            at(10, 0),
            at(12, 0), // no such chain
        ];
        let want = looked_up(&chains);
        for origins in [
            &origins[..],
            &origins[..3],
            &[],
            &[at(5, 7), at(0, 0), at(1, 0)],
        ] {
            let s = slots(&chains, origins);
            assert_eq!((s.first_chain, s.point_slots), want);
        }
        assert_eq!(want.0, [0, 1, 3, 4, 5, 7, 10]);
    }
}
