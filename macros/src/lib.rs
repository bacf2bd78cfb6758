//! `#[unit_test]`: hw3's unit tests without a second build of the library.
//!
//! The attribute keeps the function and adds a registration of it to the registry
//! `hw3::testing::UNIT_TESTS` (a [linkme](https://docs.rs/linkme/0.3) distributed slice), which
//! the runner `tests/unit.rs` runs; why hw3's unit tests are not `#[test]` is told once, in the
//! documentation of `hw3::testing`.
//!
//! The attribute reads the two test attributes hw3 uses after it, and removes them (on a plain
//! function the compiler would warn that they do nothing):
//! - `#[ignore = "reason"]` (or bare `#[ignore]`): registered as ignored, run by `--ignored`;
//! - `#[should_panic(expected = "text")]`, `#[should_panic = "text"]` (or bare `#[should_panic]`):
//!   passes only if the function panics, with a message containing `text`.
//!
//! The function takes no arguments and returns `()` (the registry holds `fn()`); a test that
//! returns a `Result` does not compile here, where libtest would accept it.
//!
//! Written on the `proc_macro` token trees alone (no `syn`): the input is a function item, and the
//! attribute needs only its name and those two attributes.
//!
//! # Errors
//! A compile error when the item is not a function, when the attribute has arguments, or when
//! `ignore` or `should_panic` is written in a form libtest would reject too.

use proc_macro::{Delimiter, Group, TokenStream, TokenTree};

/// Registers a unit test of hw3 (see the crate documentation). Takes no arguments.
#[proc_macro_attribute]
pub fn unit_test(args: TokenStream, item: TokenStream) -> TokenStream {
    if !args.is_empty() {
        return compile_error("#[unit_test] takes no arguments");
    }
    let tokens: Vec<TokenTree> = item.into_iter().collect();
    let mut kept = Vec::with_capacity(tokens.len());
    let mut ignore = String::from("None");
    let mut should_panic = String::from("None");
    let mut name = None;
    let mut i = 0;
    while i < tokens.len() {
        // An outer attribute: `#` then a bracketed group.
        if let (TokenTree::Punct(hash), Some(TokenTree::Group(group))) = (&tokens[i], tokens.get(i + 1))
            && hash.as_char() == '#'
            && group.delimiter() == Delimiter::Bracket
            && name.is_none()
        {
            match test_attribute(group) {
                Ok(Some(TestAttribute::Ignore(reason))) => ignore = format!("Some({reason})"),
                Ok(Some(TestAttribute::ShouldPanic(expected))) => should_panic = format!("Some({expected})"),
                Ok(None) => kept.extend([tokens[i].clone(), tokens[i + 1].clone()]),
                Err(message) => return compile_error(message),
            }
            i += 2;
            continue;
        }
        if let (TokenTree::Ident(keyword), Some(TokenTree::Ident(ident))) = (&tokens[i], tokens.get(i + 1))
            && keyword.to_string() == "fn"
            && name.is_none()
        {
            name = Some(ident.to_string());
        }
        kept.push(tokens[i].clone());
        i += 1;
    }
    let Some(name) = name else {
        return compile_error("#[unit_test] applies to a function");
    };
    // `r#type` is a function named `type`: the registration's static takes the bare name, the
    // registered name keeps the `r#`, as libtest prints it.
    let bare = name.strip_prefix("r#").unwrap_or(&name);
    let registration = format!(
        "#[::linkme::distributed_slice(crate::testing::UNIT_TESTS)]
         static __UNIT_TEST_{upper}: crate::testing::UnitTest = crate::testing::UnitTest {{
             name: ::core::concat!(::core::module_path!(), \"::{name}\"),
             run: {name},
             ignore: {ignore},
             should_panic: {should_panic},
         }};",
        upper = bare.to_uppercase(),
    );
    let mut out: TokenStream = kept.into_iter().collect();
    out.extend(registration.parse::<TokenStream>().expect("the registration is valid Rust"));
    out
}

enum TestAttribute {
    /// The reason as a string literal's source text (`"..."`), or `""` for a bare `#[ignore]`.
    Ignore(String),
    /// The expected text as a string literal's source text, or `""` for a bare `#[should_panic]`.
    ShouldPanic(String),
}

const SHOULD_PANIC_FORMS: &str =
    "write #[should_panic], #[should_panic = \"text\"] or #[should_panic(expected = \"text\")]";

/// `#[ignore ...]` or `#[should_panic ...]`, given the attribute's bracketed group; `Ok(None)` for
/// any other attribute, and an error for a form libtest would not accept either.
fn test_attribute(group: &Group) -> Result<Option<TestAttribute>, &'static str> {
    let inner: Vec<TokenTree> = group.stream().into_iter().collect();
    let Some(TokenTree::Ident(ident)) = inner.first() else { return Ok(None) };
    // `= "text"`: a string literal (plain or raw), as libtest asks.
    let literal_after_equals = |tokens: &[TokenTree]| match tokens {
        [TokenTree::Punct(eq), TokenTree::Literal(literal)] if eq.as_char() == '=' => {
            let text = literal.to_string();
            (text.starts_with('"') || text.starts_with("r\"") || text.starts_with("r#")).then_some(text)
        }
        _ => None,
    };
    let any_text = || "\"\"".to_string();
    match (ident.to_string().as_str(), &inner[1..]) {
        ("ignore", []) => Ok(Some(TestAttribute::Ignore(any_text()))),
        ("ignore", rest) => literal_after_equals(rest)
            .map(|reason| Some(TestAttribute::Ignore(reason)))
            .ok_or("write #[ignore] or #[ignore = \"reason\"]"),
        ("should_panic", []) => Ok(Some(TestAttribute::ShouldPanic(any_text()))),
        ("should_panic", [TokenTree::Punct(_), ..]) => literal_after_equals(&inner[1..])
            .map(|expected| Some(TestAttribute::ShouldPanic(expected)))
            .ok_or(SHOULD_PANIC_FORMS),
        ("should_panic", [TokenTree::Group(args)]) if args.delimiter() == Delimiter::Parenthesis => {
            let args: Vec<TokenTree> = args.stream().into_iter().collect();
            match args.as_slice() {
                [TokenTree::Ident(key), rest @ ..] if key.to_string() == "expected" => literal_after_equals(rest),
                _ => None,
            }
            .map(|expected| Some(TestAttribute::ShouldPanic(expected)))
            .ok_or(SHOULD_PANIC_FORMS)
        }
        ("should_panic", _) => Err(SHOULD_PANIC_FORMS),
        _ => Ok(None),
    }
}

fn compile_error(message: &str) -> TokenStream {
    format!("::core::compile_error!({message:?});").parse().expect("a compile_error! invocation is valid Rust")
}
