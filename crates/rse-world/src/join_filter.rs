//! The templates' `join` filter: minijinja's, with a fast path for what
//! our templates join most, a box's three numbers (`b.center|join(" ")`).
//! Each distinct number's text is made once per thread by minijinja's own
//! `Display` and looked up after, so the bytes are minijinja's; formatting
//! those floats again for every box of every target was a tenth of a
//! batch's time. Anything else goes to minijinja's filter as it is.

use std::cell::RefCell;
use std::fmt::Write as _;

use minijinja::value::{Kwargs, StringInput, ValueKind};
use minijinja::{Error, State, Value};
use rustc_hash::FxHashMap;

/// The fast path's bounds: its output stays small, so skipping the
/// builtin's per-item fuel charge lets no template run away.
const MAX_ITEMS: usize = 16;
const MAX_JOINER: usize = 16;
/// Distinct numbers remembered per thread before the table starts over.
const MAX_REMEMBERED: usize = 1 << 16;

thread_local! {
    static TEXT: RefCell<FxHashMap<u64, String>> = RefCell::new(FxHashMap::default());
}

/// `value|join(joiner)`, as minijinja's builtin `join` renders it.
pub(crate) fn join(
    state: &mut State,
    value: &Value,
    joiner: Option<StringInput<'_>>,
    attribute: Option<&str>,
    kwargs: Kwargs,
) -> Result<Value, Error> {
    let plain = joiner
        .as_ref()
        .is_none_or(|j| !j.is_safe() && j.as_str().len() <= MAX_JOINER);
    if plain
        && attribute.is_none()
        && kwargs.args().next().is_none()
        && value.kind() == ValueKind::Seq
        && let Some(text) = numbers(value, joiner.as_ref().map_or("", StringInput::as_str))
    {
        return Ok(Value::from(text));
    }
    minijinja::filters::join(state, value, joiner, attribute, kwargs)
}

/// The items of `seq` joined by `joiner`, if it holds at most
/// [`MAX_ITEMS`] items and every one is a float or an integer.
fn numbers(seq: &Value, joiner: &str) -> Option<String> {
    let len = seq.len()?;
    if len > MAX_ITEMS {
        return None;
    }
    let mut out = String::with_capacity(len * 8);
    TEXT.with_borrow_mut(|known| {
        for i in 0..len {
            let item = seq.get_item_by_index(i).ok()?;
            if i > 0 {
                out.push_str(joiner);
            }
            if item.is_number() && !item.is_integer() {
                let bits = f64::try_from(item.clone()).ok()?.to_bits();
                if known.len() >= MAX_REMEMBERED {
                    known.clear();
                }
                out.push_str(known.entry(bits).or_insert_with(|| item.to_string()));
            } else if item.is_integer() {
                write!(out, "{item}").ok()?;
            } else {
                return None;
            }
        }
        Some(out)
    })
}

#[cfg(test)]
mod tests {
    use minijinja::{Environment, context};

    /// `template` rendered with minijinja's `join` and with ours.
    fn both(template: &str, values: &minijinja::Value) -> (String, String) {
        let mut ours = Environment::new();
        ours.add_filter("join", super::join);
        let theirs = Environment::new();
        let render = |env: &Environment| {
            env.render_str(template, context! { v => values.clone() })
                .unwrap()
        };
        (render(&theirs), render(&ours))
    }

    #[test]
    fn joins_as_minijinja_does() {
        let floats = [
            0.1,
            1.0,
            -0.0,
            0.15,
            1e21,
            1e-7,
            123_456.789,
            f64::MAX,
            -2.5,
        ];
        for template in [
            "{{ v|join(' ') }}",
            "{{ v|join(', ') }}",
            "{{ v|join }}",
            "{{ v|join(d='|') }}",
        ] {
            let (theirs, ours) = both(template, &minijinja::Value::from(floats.to_vec()));
            assert_eq!(ours, theirs, "{template}");
            // Twice: the second time from the remembered texts.
            assert_eq!(
                both(template, &minijinja::Value::from(floats.to_vec())).1,
                theirs
            );
        }
        let mixed = minijinja::Value::from(vec![
            minijinja::Value::from(3),
            minijinja::Value::from(0.5),
            minijinja::Value::from("a"),
        ]);
        let (theirs, ours) = both("{{ v|join('-') }}", &mixed);
        assert_eq!(ours, theirs);
        let (theirs, ours) = both(
            "{{ v|join(' ') }}",
            &minijinja::Value::from((0..40).map(f64::from).collect::<Vec<_>>()),
        );
        assert_eq!(ours, theirs, "longer than the fast path");
        let (theirs, ours) = both("{{ 'abc'|join('.') }}", &minijinja::Value::UNDEFINED);
        assert_eq!(ours, theirs, "a string");
    }
}
