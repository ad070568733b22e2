//! A box of the block model as a template value: a map of `center`,
//! `size`, `half_size` (tuples of three floats) and `cells`, exactly as the
//! same fields serialized by serde would be, built without serde.
//!
//! Every world's box set becomes template values once, and serializing
//! each box through serde was a tenth of a world's template time. The
//! fields are tuples, as serde makes arrays, which the `join` filter's fast
//! path reads as slices.

use std::sync::Arc;

use minijinja::Value;
use minijinja::value::{Enumerator, Object, Tuple};
use rse_core::mesh::Block;

/// One box, metres, as templates see it (`templates/README.md`).
#[derive(Debug)]
pub(crate) struct BoxValue {
    center: Value,
    size: Value,
    half_size: Value,
    /// Cells covered: `[x0, y0, x1, y1]`, ends exclusive.
    cells: Value,
}

/// The fields, in the order serde gives a struct's fields (its order of
/// declaration), so `{{ b }}` and `b|tojson` print as they always have.
const FIELDS: &[&str] = &["center", "size", "half_size", "cells"];

impl BoxValue {
    /// `block` as a template value, its numbers tidied by `tidy`.
    pub(crate) fn value(block: &Block, tidy: fn(f64) -> f64) -> Value {
        Value::from_object(BoxValue {
            center: tuple(block.center.map(tidy)),
            size: tuple(block.half_size.map(|h| tidy(2.0 * h))),
            half_size: tuple(block.half_size.map(tidy)),
            cells: tuple(block.cells),
        })
    }
}

/// `items` as the tuple serde makes of an array.
fn tuple<T: Into<Value>, const N: usize>(items: [T; N]) -> Value {
    Value::from_object(Tuple::from(items.map(Into::into)))
}

impl Object for BoxValue {
    fn get_value(self: &Arc<Self>, key: &Value) -> Option<Value> {
        self.get_value_by_str(key.as_str()?)
    }

    fn get_value_by_str(self: &Arc<Self>, key: &str) -> Option<Value> {
        Some(
            match key {
                "center" => &self.center,
                "size" => &self.size,
                "half_size" => &self.half_size,
                "cells" => &self.cells,
                _ => return None,
            }
            .clone(),
        )
    }

    fn enumerate(self: &Arc<Self>) -> Enumerator {
        Enumerator::Str(FIELDS)
    }
}

#[cfg(test)]
mod tests {
    use minijinja::{Environment, context};
    use rse_core::mesh::Block;
    use serde::Serialize;

    use super::BoxValue;

    /// A box as templates saw it before [`BoxValue`]: serialized fields.
    #[derive(Serialize)]
    struct Serialized {
        center: [f64; 3],
        size: [f64; 3],
        half_size: [f64; 3],
        cells: [u32; 4],
    }

    /// What `template` renders with `b` as a [`BoxValue`] and as the
    /// serialized fields of the same box.
    fn both(template: &str, block: &Block) -> (String, String) {
        let mut env = Environment::new();
        env.add_filter("join", crate::render::join_filter::join);
        let render = |b: minijinja::Value| {
            let w = minijinja::Value::from(vec![1.5, 2.0, 3.0]);
            env.render_str(
                template,
                context! { v => b.get_attr("center").unwrap(), b, w },
            )
            .unwrap_or_else(|e| format!("error: {e}"))
        };
        let serialized = Serialized {
            center: block.center,
            size: block.half_size.map(|h| 2.0 * h),
            half_size: block.half_size,
            cells: block.cells,
        };
        (
            render(BoxValue::value(block, |x| x)),
            render(minijinja::Value::from(minijinja::value::Serde(&serialized))),
        )
    }

    #[test]
    fn a_box_value_is_to_templates_what_its_serialized_fields_are() {
        for (center, half_size) in [
            ([0.1, 1.0, -0.0], [0.05, 0.5, 0.0]),
            ([1e21, 1e-7, 123_456.789], [1.0, 2.5, 1e-9]),
            ([1.5, 2.0, 3.0], [0.75, 1.0, 1.5]),
        ] {
            let block = Block {
                center,
                half_size,
                cells: [1, 2, 30, 4],
            };
            for template in [
                "{{ b }}",
                "{{ b|pprint }}",
                "{{ b|tojson }}",
                "{{ b|length }} {{ b|list }} {{ b|dictsort }} {{ b.items()|list }}",
                "{{ b.center }} {{ b['size'] }} {{ b.half_size }} {{ b.cells }} {{ b.other }}",
                "{% for k in b %}{{ k }}={{ b[k] }};{% endfor %} {{ 'center' in b }}",
                "{{ b is mapping }} {{ b is sequence }} {{ b is true }} {{ b == b }}",
                "{{ b.cells|join(' ') }} {{ b.cells[2] * 2 }} {{ b.cells|sum }}",
                "{{ v }} {{ v|pprint }} {{ v|tojson }}",
                "{{ v|join(' ') }}, {{ v|join(', ') }}, {{ v|join }}, {{ v|join(d='|') }}",
                "{{ v|join(' ')|join(' ') }} {{ v|join(' ', attribute='x') }}",
                "{{ v[0] }} {{ v[2] }} {{ v[-1] }} {{ v[3] }} {{ v['x'] }}",
                "{{ v|length }} {{ v|first }} {{ v|last }} {{ v|sum }} {{ v|max }}",
                "{{ v|map('round', 1)|list }} {{ v|reverse|list }} {{ v|sort }}",
                "{% for x in v %}{{ loop.index }}:{{ x }},{% endfor %}",
                "{{ v is sequence }} {{ v is mapping }} {{ v is iterable }} {{ v is true }}",
                "{{ v == w }} {{ v == [1.5, 2.0, 3.0] }} {{ v != w }} {{ 2.0 in v }}",
                "{{ v[1:] }} {{ v|batch(2)|list }} {{ v|unique|list }}",
                "{% if v %}yes{% endif %} {{ v ~ '' }} {{ [v, v]|tojson }}",
            ] {
                let (ours, serialized) = both(template, &block);
                assert_eq!(ours, serialized, "{template} of {block:?}");
            }
        }
    }
}
