//! Tokens on links (the paper's Petri-net tokens): a link's token count
//! and who holds what in, the answers "may this seed see / use this link"
//! out. States: free → reserved (by a seed whose query targets the link)
//! → used (a message sent); reserved → free when, in a whole pass, no
//! query of the holder targets the link any more.

use std::collections::BTreeSet;

/// The tokens of one link.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LinkTokens {
    pub total: u32,
    pub used: u32,
    /// Seeds (run ordinals) holding one reserved token each, in the order
    /// they reserved.
    pub reserved: Vec<usize>,
    /// Holders whose query targeted the link in the current pass.
    touched: BTreeSet<usize>,
}

impl LinkTokens {
    pub fn new(total: u32) -> LinkTokens {
        LinkTokens {
            total,
            ..LinkTokens::default()
        }
    }

    pub fn free(&self) -> u32 {
        self.total - self.used - self.reserved.len() as u32
    }

    pub fn holds(&self, seed: usize) -> bool {
        self.reserved.contains(&seed)
    }

    /// A navigation link (no tokens at all) or one with a free token: what
    /// a query that names no id sees. A reserved token is hidden from such
    /// queries, the holder's own included: the module that reserved it
    /// names the link (the spiral's tip must not send a second branch).
    pub fn visible(&self) -> bool {
        self.total == 0 || self.free() > 0
    }

    /// A query of `seed` names this link (`id_test`): it keeps or takes a
    /// reservation. False when every token is used or held by others.
    pub fn target(&mut self, seed: usize) -> bool {
        if self.total == 0 {
            return true;
        }
        if self.holds(seed) {
            self.touched.insert(seed);
            return true;
        }
        if self.free() > 0 {
            self.reserved.push(seed);
            self.touched.insert(seed);
            return true;
        }
        false
    }

    /// `?X` of `seed` touched the link's edge: its reservation, else a free
    /// token, becomes used. True when a message is to be sent.
    pub fn use_token(&mut self, seed: usize) -> bool {
        if let Some(i) = self.reserved.iter().position(|s| *s == seed) {
            self.reserved.remove(i);
            self.used += 1;
            return true;
        }
        if self.free() > 0 {
            self.used += 1;
            return true;
        }
        false
    }

    /// End of a pass: reservations whose holder did not target the link
    /// in it return to free.
    pub fn end_pass(&mut self) {
        let touched = std::mem::take(&mut self.touched);
        self.reserved.retain(|s| touched.contains(s));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reservation_bars_others_until_released() {
        let mut t = LinkTokens::new(1);
        assert!(t.target(3));
        assert!(!t.visible());
        assert!(!t.target(4));
        assert!(t.target(3));
        t.end_pass();
        assert_eq!(t.reserved, vec![3]);
        // A pass where seed 3 no longer targets the link frees the token.
        t.end_pass();
        assert!(t.reserved.is_empty());
        assert!(t.use_token(4));
        assert!(!t.use_token(3));
        assert_eq!((t.used, t.free()), (1, 0));
    }

    #[test]
    fn a_zero_token_link_guides_but_never_sends() {
        let mut t = LinkTokens::new(0);
        assert!(t.visible() && t.target(0));
        assert!(!t.use_token(0));
    }

    #[test]
    fn the_holder_uses_its_reservation() {
        let mut t = LinkTokens::new(2);
        assert!(t.target(1));
        assert!(t.use_token(1));
        assert_eq!((t.used, t.free(), t.reserved.len()), (1, 1, 0));
    }
}
