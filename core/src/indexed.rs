//! [`IndexedExt::indexed`]: `Iterator::enumerate` without a panic path.
//!
//! The standard `Enumerate` increments its count with the *caller's* overflow checks
//! (`#[rustc_inherit_overflow_checks]`), so with `overflow-checks = true` in release (this
//! workspace's profile) every `enumerate()` whose bound the optimiser cannot see leaves a call
//! to the overflow panic in the flight code: the C library's link-time abort-free proof
//! (docs/c-api.md) found them. The count cannot overflow here (no iterator in the core yields
//! `usize::MAX` items: every one walks a fixed-capacity array or a bounded range), and
//! [`Indexed`] says so by counting with wrapping arithmetic. Items, order and indices are those
//! of `enumerate()`, forwards and backwards.

use core::iter::FusedIterator;

/// The iterator of [`IndexedExt::indexed`]: `(index, item)` pairs, as `enumerate()` yields.
#[derive(Clone, Debug)]
pub struct Indexed<I> {
    iter: I,
    count: usize,
}

impl<I: Iterator> Iterator for Indexed<I> {
    type Item = (usize, I::Item);

    #[inline]
    fn next(&mut self) -> Option<Self::Item> {
        let item = self.iter.next()?;
        let index = self.count;
        self.count = self.count.wrapping_add(1);
        Some((index, item))
    }

    #[inline]
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.iter.size_hint()
    }

    #[inline]
    fn nth(&mut self, n: usize) -> Option<Self::Item> {
        let item = self.iter.nth(n)?;
        let index = self.count.wrapping_add(n);
        self.count = index.wrapping_add(1);
        Some((index, item))
    }
}

impl<I: DoubleEndedIterator + ExactSizeIterator> DoubleEndedIterator for Indexed<I> {
    #[inline]
    fn next_back(&mut self) -> Option<Self::Item> {
        let item = self.iter.next_back()?;
        // After taking the last item, `len()` items remain before it.
        Some((self.count.wrapping_add(self.iter.len()), item))
    }
}

impl<I: ExactSizeIterator> ExactSizeIterator for Indexed<I> {}

impl<I: FusedIterator> FusedIterator for Indexed<I> {}

/// `indexed()` for every iterator.
pub trait IndexedExt: Iterator + Sized {
    /// `(index, item)` pairs from 0, as `enumerate()`, with no overflow check (see the module).
    #[inline]
    fn indexed(self) -> Indexed<Self> {
        Indexed {
            iter: self,
            count: 0,
        }
    }

    /// The index of the first item that satisfies `predicate`, as `position()`, with no
    /// overflow check.
    #[inline]
    fn index_of(self, mut predicate: impl FnMut(Self::Item) -> bool) -> Option<usize> {
        self.indexed()
            .find_map(|(index, item)| predicate(item).then_some(index))
    }
}

impl<I: Iterator> IndexedExt for I {}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::IndexedExt;
    use std::vec::Vec;

    #[test]
    fn yields_what_enumerate_yields_forwards_backwards_and_skipped() {
        let data = [3.0, 1.0, 4.0, 1.0, 5.0, 9.0, 2.0];
        let ours: Vec<_> = data.iter().indexed().collect();
        let std: Vec<_> = data.iter().enumerate().collect();
        assert_eq!(ours, std);
        let ours: Vec<_> = data.iter().indexed().take(5).rev().collect();
        let std: Vec<_> = data.iter().enumerate().take(5).rev().collect();
        assert_eq!(ours, std);
        let ours: Vec<_> = data.iter().indexed().skip(2).step_by(2).collect();
        let std: Vec<_> = data.iter().enumerate().skip(2).step_by(2).collect();
        assert_eq!(ours, std);
        let mut ours = data.iter().indexed();
        let mut std = data.iter().enumerate();
        assert_eq!(ours.nth(2), std.nth(2));
        assert_eq!(ours.next_back(), std.next_back());
        assert_eq!(ours.next(), std.next());
        assert_eq!(ours.len(), std.len());
        assert_eq!(data.iter().index_of(|&x| x > 4.0), Some(4));
        assert_eq!(data.iter().index_of(|&x| x > 10.0), None);
    }
}
