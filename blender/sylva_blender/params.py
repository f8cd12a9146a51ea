"""A model's parameters as Blender properties, from the directive schema (`sylva describe`,
`Model.params`): one item per number or whole-number parameter, with its range, the model's
value and the directive's default, drawn in the redo panel; a value out of the range is held
at its end (when the tree is built), and the info button beside it shows the parameter's meaning as its tooltip.

An operator's properties are fixed when it is registered, so the parameters of whatever model
is chosen live in a collection of (name, value, min, max, doc) items rather than in classes
generated per model; only the values that differ from the model's own reach the build, as
`--set` values."""
from __future__ import annotations

import bpy
from bpy.props import BoolProperty, FloatProperty, IntProperty, StringProperty

# the operator's own fields say these; their schema rows would be a second way to set them
HANDLED = {"seed", "derive"}
SHOWN = {"number", "integer"}


def _clamp(it, v: float) -> float:
    return min(max(v, it.min), it.max)


def _get(it) -> float:
    return float(it.ivalue) if it.integer else it.value


def _put(it, v: float) -> None:
    if it.integer:
        it.ivalue = int(round(_clamp(it, v)))
    else:
        it.value = _clamp(it, v)


class SylvaParam(bpy.types.PropertyGroup):
    # name: PropertyGroup's own, the parameter's name
    value: FloatProperty(name="Value", precision=4)
    ivalue: IntProperty(name="Value")
    integer: BoolProperty()
    min: FloatProperty()
    max: FloatProperty()
    model_value: FloatProperty(description="the model's own value: not sent when unchanged")
    default: StringProperty()
    unit: StringProperty()
    doc: StringProperty()


# the rows of each model (its schema, asked once: describe and its JSON cost more than the
# rows), by the sylva.Model object the add-on keeps while its file is unchanged
_rows: dict = {}


def rows(model) -> list:
    """The model's parameters shown as rows (sylva.Param), asked of its schema once."""
    got = _rows.get(id(model))
    if got is None or got[0] is not model:
        got = (model, [p for p in model.params.values() if p.type in SHOWN and p.name not in HANDLED
                       and not isinstance(p.value, (list, str)) and p.value is not None])
        if len(_rows) >= 32:
            del _rows[next(iter(_rows))]
        _rows[id(model)] = got
    return got[1]


def free() -> None:
    _rows.clear()


def fill(params, model, keep: bool) -> bool:
    """Fill the collection with the model's parameters at the model's values; keep: values the
    caller already gave by name (bpy.ops(..., params=[{"name": …, "value": …}])) stay. Returns
    whether any was given (else every row is at the model's value, and there is no --set)."""
    given = {it.name: (it.ivalue, it.value) for it in params} if keep else {}
    params.clear()
    for p in rows(model):
        it = params.add()
        it.name = p.name
        it.integer = p.type == "integer"
        it.min = -3.0e38 if p.min is None else max(float(p.min), -3.0e38)
        it.max = 3.0e38 if p.max is None else min(float(p.max), 3.0e38)
        it.doc = p.doc
        it.unit = p.unit
        it.default = "" if p.default is None else f"{p.default:g}" if isinstance(p.default, (int, float)) else str(p.default)
        _put(it, float(p.value))
        it.model_value = _get(it)
        if p.name in given:
            _put(it, given[p.name][0] if it.integer else given[p.name][1])
    return bool(given)


def overrides(params) -> dict:
    """The --set values: the parameters whose value differs from the model's, held in the
    schema's range (written back, so that the redo panel shows it), at the precision a user
    types (a float property holds 0.2 as 0.2000000029)."""
    out = {}
    for it in params:
        _put(it, _get(it))
        v = _get(it)
        if v != it.model_value:
            out[it.name] = v if it.integer else float(f"{v:.6g}")
    return out


def tooltip(it) -> str:
    rng = f"{it.min:g} – {it.max:g}" if abs(it.min) < 1e9 and abs(it.max) < 1e9 else "any"
    unit = f" {it.unit}" if it.unit else ""
    return f"{it.name}: {it.doc}. Range {rng}{unit}; default {it.default or '—'}"


class SYLVA_OT_param_info(bpy.types.Operator):
    """The parameter's meaning, range and default (its tooltip; clicking does nothing)"""
    bl_idname = "sylva.param_info"
    bl_label = "Parameter"
    bl_options = {"INTERNAL"}
    text: StringProperty(options={"HIDDEN"})

    @classmethod
    def description(cls, context, properties):
        return properties.text

    def execute(self, context):
        return {"CANCELLED"}


def draw(layout, params) -> None:
    if not len(params):
        return
    box = layout.box()
    box.label(text="Parameters (the directive schema)")
    col = box.column(align=True)
    for it in params:
        row = col.row(align=True)
        row.prop(it, "ivalue" if it.integer else "value", text=it.name)
        row.operator(SYLVA_OT_param_info.bl_idname, text="", icon="INFO", emboss=False).text = tooltip(it)


CLASSES = (SylvaParam, SYLVA_OT_param_info)
