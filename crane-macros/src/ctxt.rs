//! Error collection (after serde_derive's `Ctxt`).
//!
//! Every stage reports problems here instead of returning at the first one,
//! so that the user sees all mistakes of a declaration at once. The errors
//! are combined into one [`syn::Error`] at the end.

use std::cell::RefCell;
use std::fmt::Display;

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;

/// Collects the errors of one macro invocation.
#[derive(Default)]
pub struct Ctxt {
    errors: RefCell<Vec<syn::Error>>,
}

impl Ctxt {
    /// An empty context.
    pub fn new() -> Self {
        Self::default()
    }

    /// An error that points at `span`.
    pub fn error_at(&self, span: Span, message: impl Display) {
        self.errors.borrow_mut().push(syn::Error::new(span, message));
    }

    /// An error that points at all of `tokens` (from their first to their
    /// last token).
    pub fn error_spanned_by(&self, tokens: impl ToTokens, message: impl Display) {
        self.errors
            .borrow_mut()
            .push(syn::Error::new_spanned(tokens.into_token_stream(), message));
    }

    /// An error from syn (a parse error).
    pub fn syn_error(&self, error: syn::Error) {
        self.errors.borrow_mut().push(error);
    }

    /// Whether anything was reported so far.
    pub fn has_errors(&self) -> bool {
        !self.errors.borrow().is_empty()
    }

    /// How many errors were reported so far (to tell whether a stage added
    /// any).
    pub fn error_count(&self) -> usize {
        self.errors.borrow().len()
    }

    /// `Err` with all reported errors combined, in the order they were
    /// reported, or `Ok` if there were none.
    pub fn check(self) -> Result<(), syn::Error> {
        let mut errors = self.errors.into_inner().into_iter();
        let Some(mut combined) = errors.next() else {
            return Ok(());
        };
        for error in errors {
            combined.combine(error);
        }
        Err(combined)
    }
}

/// A token range (first and last span) that [`syn::Error::new_spanned`] can
/// point at: on stable Rust spans cannot be joined, but an error spanned by
/// two tokens underlines everything from the first to the second.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// Span of the first token.
    pub first: Span,
    /// Span of the last token.
    pub last: Span,
}

impl SpanRange {
    /// The range of a single token.
    pub fn single(span: Span) -> Self {
        Self {
            first: span,
            last: span,
        }
    }

    /// From the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> Self {
        Self {
            first: self.first,
            last: other.last,
        }
    }
}

impl ToTokens for SpanRange {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        // Two punctuation tokens that carry the two spans.
        let mut first = proc_macro2::Punct::new('<', proc_macro2::Spacing::Alone);
        first.set_span(self.first);
        let mut last = proc_macro2::Punct::new('>', proc_macro2::Spacing::Alone);
        last.set_span(self.last);
        tokens.extend([proc_macro2::TokenTree::from(first), proc_macro2::TokenTree::from(last)]);
    }
}
