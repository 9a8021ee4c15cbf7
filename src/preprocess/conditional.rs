//! The stack of open `#if` groups of one file. Input: conditional
//! directives in order. Output: whether text lines are currently kept, and
//! which directives are misplaced.

use std::ops::Range;

struct Group {
    /// The enclosing region is kept (otherwise nothing here is evaluated).
    parent_active: bool,
    /// The current branch is kept.
    active: bool,
    /// Some branch of this group has been taken already.
    taken: bool,
    seen_else: bool,
    /// The opening directive, for "unterminated".
    span: Range<usize>,
}

#[derive(Default)]
pub(crate) struct Conditionals {
    stack: Vec<Group>,
}

/// A misplaced `#elif`/`#else`/`#endif`.
pub(crate) enum Misplaced {
    WithoutIf,
    AfterElse,
}

impl Conditionals {
    pub fn active(&self) -> bool {
        self.stack.last().map_or(true, |g| g.active)
    }

    /// `#if`-like with its condition (not evaluated when inactive: pass `false`).
    pub fn push(&mut self, cond: bool, span: Range<usize>) {
        let parent_active = self.active();
        let active = parent_active && cond;
        self.stack.push(Group {
            parent_active,
            active,
            taken: active,
            seen_else: false,
            span,
        });
    }

    /// Whether an `#elif` here needs its condition evaluated.
    pub fn elif_needs_eval(&self) -> bool {
        self.stack
            .last()
            .is_some_and(|g| g.parent_active && !g.taken && !g.seen_else)
    }

    pub fn elif(&mut self, cond: bool) -> Result<(), Misplaced> {
        let g = self.stack.last_mut().ok_or(Misplaced::WithoutIf)?;
        if g.seen_else {
            return Err(Misplaced::AfterElse);
        }
        g.active = g.parent_active && !g.taken && cond;
        g.taken |= g.active;
        Ok(())
    }

    pub fn else_(&mut self) -> Result<(), Misplaced> {
        let g = self.stack.last_mut().ok_or(Misplaced::WithoutIf)?;
        if g.seen_else {
            return Err(Misplaced::AfterElse);
        }
        g.seen_else = true;
        g.active = g.parent_active && !g.taken;
        g.taken = true;
        Ok(())
    }

    pub fn endif(&mut self) -> Result<(), Misplaced> {
        self.stack.pop().map(|_| ()).ok_or(Misplaced::WithoutIf)
    }

    /// The opening spans of groups still open at the end of the file.
    pub fn unterminated(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.stack.iter().map(|g| g.span.clone())
    }
}
