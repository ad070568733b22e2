//! The templates' `join` filter: minijinja's, with a fast path for what
//! our templates join most, a box's three numbers (`b.center|join(" ")`).
//! Each number's text is made by minijinja's own `Display` and remembered
//! per thread in a small table, so the bytes are minijinja's; formatting
//! those floats again for every box of every target was a tenth of a
//! batch's time. Anything else goes to minijinja's filter as it is.

use std::cell::RefCell;
use std::fmt::Write as _;

use minijinja::value::{Kwargs, StringInput, Tuple, ValueKind};
use minijinja::{Error, State, Value};

/// The fast path's bounds: its output stays small, so skipping the
/// builtin's per-item fuel charge lets no template run away.
const MAX_ITEMS: usize = 16;
const MAX_JOINER: usize = 16;

/// Texts remembered per thread: a table of this many slots, each number
/// in the slot its bits hash to (a number meeting another in its slot is
/// formatted again: slower, never wrong).
const SLOT_BITS: u32 = 12;

/// A thread's remembered number texts, and the buffer a join is written
/// into (kept: a join's text is copied into its value, so a new buffer
/// per join would be an allocation and a free for nothing).
struct Texts {
    slots: Vec<Option<(u64, String)>>,
    joined: String,
}

thread_local! {
    static TEXTS: RefCell<Texts> = RefCell::new(Texts {
        slots: vec![None; 1 << SLOT_BITS],
        joined: String::new(),
    });
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
    if plain && attribute.is_none() && kwargs.args().next().is_none() {
        let joiner = joiner.as_ref().map_or("", StringInput::as_str);
        // A box's vectors are tuples (`BoxValue`): their items as a slice.
        let text = if let Some(tuple) = value.downcast_object_ref::<Tuple>() {
            (tuple.len() <= MAX_ITEMS)
                .then(|| numbers(tuple.iter().cloned(), joiner))
                .flatten()
        } else if value.kind() == ValueKind::Seq
            && let Some(len @ ..=MAX_ITEMS) = value.len()
        {
            let items = (0..len).map(|i| value.get_item_by_index(i).unwrap_or_default());
            numbers(items, joiner)
        } else {
            None
        };
        if let Some(text) = text {
            return Ok(text);
        }
    }
    minijinja::filters::join(state, value, joiner, attribute, kwargs)
}

/// `items` joined by `joiner` as a string value, if every one is a float
/// or an integer.
fn numbers(items: impl Iterator<Item = Value>, joiner: &str) -> Option<Value> {
    TEXTS.with_borrow_mut(|Texts { slots, joined }| {
        joined.clear();
        for (i, item) in items.enumerate() {
            if i > 0 {
                joined.push_str(joiner);
            }
            if item.is_integer() {
                write!(joined, "{item}").ok()?;
            } else if item.is_number() {
                let bits = f64::try_from(item.clone()).ok()?.to_bits();
                // Fibonacci hashing: the top bits of the product.
                let slot = &mut slots
                    [(bits.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> (64 - SLOT_BITS)) as usize];
                match slot {
                    Some((known, text)) if *known == bits => joined.push_str(text),
                    _ => {
                        let text = item.to_string();
                        joined.push_str(&text);
                        *slot = Some((bits, text));
                    }
                }
            } else {
                return None;
            }
        }
        Some(Value::from(joined.as_str()))
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
            // A box's vectors are tuples.
            let tuple = minijinja::Value::from_object(minijinja::value::Tuple::from(
                floats.map(minijinja::Value::from),
            ));
            let (theirs, ours) = both(template, &tuple);
            assert_eq!(ours, theirs, "{template} of a tuple");
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
