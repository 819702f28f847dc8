"""The exported system (:class:`~.statespace.StateSpace`) as C99: ``compensator.h``/``.c``
(``tc_init``/``tc_reset``/``tc_step``/``tc_reference`` on a caller-owned state struct, no
allocation, no library beyond ``exp`` and ``pow``); ``stream.c``, the driver that reads CSV rows
on stdin and prints the corrections, is :mod:`.driver`'s.

Build and run: ``cc compensator.c stream.c -lm -o stream && ./stream < campaign.csv``.
"""

from __future__ import annotations

import math

from ....core.io import marks as missing_marks
from ....core.io.derived import rendered
from ....core.io.derived import sources as sources_of
from ....core.timerule import C_REPEAT_RULE, C_TIME_RULE
from .forest import forest_arrays
from .laws import UNBOUNDED
from .recurrent import net_arrays, net_inputs
from .statespace import StateSpace
from .text import banner, correction_names
from .watch_c import FUNCTIONS as MONITOR_FUNCTIONS
from .watch_c import header_part as monitor_header
from .watch_c import monitor_arrays
from .watch_c import state_part as monitor_state

ADAPT_CODES = {"none": 0, "bias": 1, "rls": 2}


def number(v: float) -> str:
    """A double literal that reads back to the same double."""
    if math.isinf(v):
        return "HUGE_VAL" if v > 0 else "-HUGE_VAL"
    return repr(float(v))


def _array(name: str, values, shape: tuple[int, ...], kind: str = "double") -> str:
    dims = "".join(f"[{max(d, 1)}]" for d in shape)
    literal = number if kind == "double" else (lambda v: str(int(v)))
    return f"static const {kind} {name}{dims} = {_braced(values, len(shape), literal)};"


def _ints(name: str, values) -> str:
    items = ", ".join(str(int(v)) for v in values) or "0"
    return f"static const int {name}[{max(len(values), 1)}] = {{{items}}};"


def _braced(values, rank: int, literal=number) -> str:
    """A nested C initialiser; an empty dimension holds one zero (C has no empty arrays)."""
    if rank == 0:
        return literal(values)
    items = [_braced(v, rank - 1, literal) for v in values] or [
        _braced([] if rank > 1 else 0.0, rank - 1, literal)]
    return "{" + ", ".join(items) + "}"


def c_string(text: str) -> str:
    """``text`` as an ASCII C string literal: a lab's ``T0 [°C]`` as its UTF-8 bytes, each
    non-ASCII one an octal escape (a hex escape would swallow the hex digits after it)."""
    out = []
    for byte in str(text).encode("utf-8"):
        char = chr(byte)
        out.append(f"\\{byte:03o}" if byte > 126 or byte < 32 or char in '"\\?' else char)
    return '"' + "".join(out) + '"'


def _lab_names(ss: StateSpace) -> str:
    """The lab's headers the stream reads as contract names (``{lab, contract}`` pairs), the
    scale and offset it converts each one's cells by to the contract's unit (µm, °C, s: 1 and
    0 for a header only renamed) and its run-number column (``data.roles.campaign``: a new
    value starts a campaign), from the provenance
    (:func:`thermocomp.shell.stages.export.export`)."""
    pairs = [(raw, contract, 1.0, 0.0)
             for contract, raws in ss.provenance.get("lab_names", {}).items()
             for raw in ([raws] if isinstance(raws, str) else raws)]
    pairs += [(raw, contract, scale, offset)
              for raw, (contract, scale, offset) in ss.provenance.get("lab_units", {}).items()]
    items = ", ".join(f"{{{c_string(raw)}, {c_string(c)}}}" for raw, c, _, _ in pairs) or '{"", ""}'
    units = ", ".join(f"{{{number(a)}, {number(b)}}}" for _, _, a, b in pairs) or "{1.0, 0.0}"
    run = ss.provenance.get("run_column")
    # the inputs a PLC's status word packs (data.bits; {input, the word's header}, the bit):
    # stream.c decodes the word where the rows give it in place of the bits (lead91)
    words = sorted((ss.provenance.get("bits") or {}).items())
    word_items = ", ".join(f"{{{c_string(c)}, {c_string(w)}}}" for c, (w, _) in words) or '{"", ""}'
    word_bits = ", ".join(str(int(b)) for _, (_, b) in words) or "0"
    return (f"#define TC_N_LAB_NAMES {len(pairs)}\n"
            f"static const char *const TC_LAB_NAMES[{max(len(pairs), 1)}][2] = {{{items}}};"
            "  /* {the lab's header, the contract name} */\n"
            "/* {scale, offset}: a cell under the lab's header k is read as value * scale + offset\n"
            "   in the contract's unit (um, degC, s), as the model's reader converted it */\n"
            f"static const double TC_LAB_UNITS[{max(len(pairs), 1)}][2] = {{{units}}};\n"
            f"#define TC_N_WORD_BITS {len(words)}\n"
            f"static const char *const TC_WORD_BITS[{max(len(words), 1)}][2] = {{{word_items}}};"
            "  /* {an input, the status word (data.bits) whose bit it is} */\n"
            f"static const int TC_WORD_BIT[{max(len(words), 1)}] = {{{word_bits}}};\n"
            f"static const char *const TC_RUN_COLUMN = {c_string(run or '')};"
            "  /* a new value starts a campaign (\"\": none) */\n"
            f"static const char *const TC_CLOCK_COLUMN = "
            f"{c_string(ss.provenance.get('clock_column') or '')};"
            "  /* the time of day joined to the date column's cell (\"\": none) */\n"
            f"#define TC_ELAPSED {int(bool(ss.provenance.get('elapsed')))}"
            "   /* data.time=elapsed: the time a logger's h:mm:ss since the start (iso67) */\n"
            f"#define TC_SLASHED {int(ss.provenance.get('slashed') or 0)}"
            "   /* data.time's dates with slashes: 1 day first, 2 month first (keysight70) */\n"
            f"#define TC_DAY_SECONDS {int(bool(ss.provenance.get('day_seconds')))}"
            "   /* the time seconds since midnight, a day added as it passes (lead91) */\n"
            f"#define TC_PAUSE_S {number(float(ss.provenance.get('pause_s') or 0.0))}"
            "   /* data.runs_at_pauses: a longer step of the time starts a campaign (0: none) */\n"
            f"static const char *const TC_THOUSANDS = "
            f"{c_string(ss.provenance.get('thousands') or '')};"
            "  /* data.thousands: the digits' grouping mark (\"\": none) */\n"
            + _twins_refused(ss) + _raw_file(ss))


def _twins_refused(ss: StateSpace) -> str:
    """(cin103) The headers an input is read by whose copy, its values apart, the model's reader
    refuses (:func:`thermocomp.core.io.twins.copy_refused`, from the provenance): stream.c
    compares such a copy with the input's column row by row and refuses the file where they
    differ."""
    heads = list(ss.provenance.get("twins_refused") or [])
    items = ", ".join(c_string(h) for h in heads) or '""'
    return (f"#define TC_N_TWINS_REFUSED {len(heads)}\n"
            f"static const char *const TC_TWIN_REFUSED[{max(len(heads), 1)}] = {{{items}}};"
            "  /* a copy of these headers, its values apart: refused, as the reader refuses it */\n")


def _derived_references(ss: StateSpace) -> str:
    """The reference of each target derived from error columns (``data.derive``, in the
    provenance) where a row does not carry the column itself: the reader's arithmetic of the
    error columns ``TC_SOURCE_NAMES`` (``r``, contract names, in um as read), generated from its
    parsed tree (:func:`thermocomp.core.io.derived.rendered`; small72: the stream learned from
    none).  A macro: compensator.c, which includes the header too, uses none of it."""
    derive = {t: ss.provenance["derive"][t] for t in ss.targets
              if t in (ss.provenance.get("derive") or {})}
    sources = list(dict.fromkeys(c for t, text in derive.items() for c in sources_of(t, text)))
    cases = "".join(f"(i) == {ss.targets.index(t)} ? "
                    + rendered(t, text, lambda c: f"(r)[{sources.index(c)}]", number) + " : "
                    for t, text in derive.items())
    names = ", ".join(map(c_string, [*sources, ""]))
    return ("/* a target derived from error columns (data.derive): where a row does not carry it,\n"
            "   its reference is the reader's arithmetic of the error columns TC_SOURCE_NAMES\n"
            "   (r, um; NAN where one is missing; NAN for a target measured itself) */\n"
            f"#define TC_N_SOURCES {len(sources)}\n"
            f"static const char *const TC_SOURCE_NAMES[TC_N_SOURCES + 1] = {{{names}}};\n"
            # ((void)(r): read, where no target is derived, so no compiler says r is unused)
            f"#define TC_DERIVED_REFERENCE(i, r) ((void)(r), {cases}NAN)")


ENCODINGS = {"utf-8": 0, "cp1252": 1, "latin-1": 2}


def _raw_file(ss: StateSpace) -> str:
    """How the lab's raw file is read (streamraw65): its character set (``data.encoding``: a
    Windows logger's cp1252 header bytes decoded to the UTF-8 of ``TC_LAB_NAMES``) and the marks
    it writes for a value not measured (``data.missing_values``: read as an empty cell)."""
    marks = [str(m) for m in ss.provenance.get("missing_values") or ()]
    items = ", ".join(map(c_string, marks)) or '""'
    numbers = missing_marks.values(marks)       # (-9999: by value, however a cell writes it)
    code = ENCODINGS.get(str(ss.provenance.get("encoding") or "utf-8"), 0)
    return (f"#define TC_ENCODING {code}   /* data.encoding: 0 utf-8, 1 cp1252, 2 latin-1 */\n"
            f"#define TC_N_MISSING {len(marks)}\n"
            f"static const char *const TC_MISSING[{max(len(marks), 1)}] = {{{items}}};"
            "  /* data.missing_values: a cell holding one is a missing value */\n"
            f"#define TC_N_MISSING_VALUES {len(numbers)}\n"
            f"static const double TC_MISSING_VALUE[{max(len(numbers), 1)}] = "
            f"{{{', '.join(map(repr, numbers)) or '0.0'}}};"
            "  /* its numbers: a cell of that value, however written, is one */")


def _pattern_constants(ss: StateSpace) -> list:
    """The training pattern (:mod:`.statespace`); without one: scale 1, never consulted."""
    n = len(ss.inputs)
    basis = ss.pattern_basis or [[0.0] for _ in range(n)]
    rank = len(basis[0]) if ss.pattern else 0
    return [_array("PATTERN_MEAN", ss.pattern_mean or [0.0] * n, (n,)),
            _array("PATTERN_SCALE", ss.pattern_scale or [1.0] * n, (n,)),
            _array("PATTERN_BASIS", basis, (n, max(rank, 1))),
            f"static const double PATTERN_TOL = {number(ss.pattern_tol)};",
            f"static const int PATTERN_RANK = {rank};",
            f"static const int PATTERN = {int(ss.pattern)};"]


def _spread(columns: list, values: list, n: int) -> list:
    """``values`` at ``columns`` of a row of ``n`` zeros."""
    row = [0.0] * n
    for j, v in zip(columns, values):
        row[j] = float(v)
    return row


def header(ss: StateSpace) -> str:
    n, m, taps = len(ss.inputs), len(ss.targets), len(ss.fir)
    names = ", ".join(map(c_string, ss.inputs))
    errors = ", ".join(map(c_string, ss.targets))
    outs = ", ".join(map(c_string, correction_names(ss.targets)))
    return f"""{banner(ss, "/*", " *", " */")}
#ifndef THERMOCOMP_COMPENSATOR_H
#define THERMOCOMP_COMPENSATOR_H

#define TC_N_INPUTS {n}
#define TC_N_OUTPUTS {m}
#define TC_N_LAWS {len(ss.laws)}   /* linear laws summed into the outputs (LAW_TARGET) */
#define TC_N_SETS {max(ss.law_set or [0]) + 1}   /* the model's laws, and each fallback model's (LAW_SET) */
#define TC_N_AMBIENT {len(ss.ambient_inputs)}   /* inputs whose first sample is the ambient (ATI) */
#define TC_AMBIENT_GIVEN {int(ss.ambient_given)}   /* 1: the ambient is given per campaign (tc_set_ambient) */
#define TC_AMBIENT_OPTIONAL {int(ss.ambient_optional)}   /* 1: ... a campaign without it still starts */
#define TC_TAPS {taps}
#define TC_DEPTH {ss.depth}
#define TC_N_LAGS {len(ss.taus)}
#define TC_N_POWERS {len(ss.powers)}   /* powers of machine states (Hammerstein) */
#define TC_N_DERIVED {len(ss.derived)}   /* a diagnosed model's derived inputs (products, lags) */
#define TC_N_INITIAL {len(ss.initial)}   /* a diagnosed lag's initial-state transient (directions) */
#define TC_N_STATE_GAIN {len(ss.clamp_states)}   /* states scaling the clamp's gain (inputs_product) */
#define TC_N_SWITCHES {len(ss.switch_input)}   /* machine states whose switching a forest reads (arx_rf) */
#define TC_N_FEATURES {len(ss.switch_feature)}   /* the forests' features: a state's ramp per tau */
#define TC_N_FORESTS {len(ss.forest_target)}
#define TC_N_TREES {len(ss.tree_root)}
#define TC_N_NODES {len(ss.node_left)}
#define TC_TREE_DEPTH {ss.tree_depth}   /* the longest walk from a root to a leaf */
#define TC_N_LSTM {len(ss.lstm_target)}   /* lstm networks (one per target or blend member) */
#define TC_LSTM_HIDDEN {ss.lstm_hidden}   /* their hidden size H (gates: 4 H rows, torch's i, f, g, o) */
#define TC_LSTM_LAYERS {ss.lstm_layers}
#define TC_LSTM_WIDTH {ss.lstm_width}   /* a layer's input row: max(TC_LSTM_INPUTS, H) */
#define TC_LSTM_INPUTS {net_inputs(ss)}   /* layer 0's: the model's columns, each a feature of [x, lags] */
#define TC_SWITCH_RAW_TIME {int(ss.switch_raw_time)}   /* 1: the ramp's time as read, 0: the stream's clock */
#define TC_WIDTH (TC_N_INPUTS + TC_N_POWERS + TC_N_DERIVED + TC_N_INITIAL)   /* a law's inputs */
#define TC_USES_TIME {int(ss.uses_time)}
#define TC_SUBSTITUTE_TIME {int(ss.substitute_time)}   /* a bad time: previous + one period */
#define TC_SKIP_REPEATS {int(ss.skip_repeats)}   /* (dup99) a row written again: skipped */
#define TC_GUARD {int(ss.guard)}   /* correction bound and rate limit */
#define TC_GUARD_INPUTS {int(ss.guard and ss.guard_inputs)}   /* the bound follows the inputs (pattern) */
#define TC_ADAPT {ADAPT_CODES[ss.adapt]}   /* learned from reference measurements: 1 bias, 2 gain and bias */
{monitor_header(ss)}
/* Everything the compensator remembers between samples; the caller owns it.  Plain data, no
   pointers: its bytes saved after a tc_step and copied back by a new process of the same build
   resume the campaign there (a restart that calls tc_init mid-campaign starts a campaign at
   its next sample, and a model of changes from a campaign's first sample misses the warm-up
   before it). */
typedef struct {{
    int first;                                  /* 1: the next sample starts a campaign */
    double buf[TC_TAPS][TC_N_INPUTS];           /* raw inputs, newest first (FIR denoiser) */
    double ref[TC_N_INPUTS];                    /* first-sample reference */
    double v0[TC_N_INPUTS];                     /* the first value (derived inputs' frame) */
    double x0[2][TC_N_INPUTS];                  /* the first sample's x and excess (inputs_product) */
    double by_prev[{max(len(ss.clamp_states), 1)}];   /* the clamp's states at the last sample */
    double by_held[{max(len(ss.clamp_states), 1)}];   /* ... at the one before the first excess */
    int excessed;                               /* 1: an excess seen in this campaign */
    int by_outright[TC_N_OUTPUTS];              /* 1: out at the campaign's first sample: outright */
    double last[TC_N_INPUTS];                   /* the last finite value (a held signal's) */
    int seen[TC_N_INPUTS];                      /* 1: a value seen in this campaign */
    double a0;                                  /* the campaign's initial ambient */
    double ambient_c;                           /* ... as given (tc_set_ambient; NAN: not yet) */
    double t0;                                  /* the campaign's first sample time, s */
    double start[{max(len(ss.initial), 1)}];    /* a transient's w . (c(0) - A0) (0: not yet) */
    int started[{max(len(ss.initial), 1)}];     /* 1: a transient's sensors seen */
    /* per channel: [0] the measured inputs, [1] their excess over the envelope */
    double hist[2][{max(ss.depth, 1)}][TC_N_INPUTS];  /* past referenced inputs, x(t-1) first */
    double z[2][{max(len(ss.taus), 1)}];        /* first-order lags */
    double y[2][TC_N_LAWS];                     /* previous output of each law (AR feedback) */
    int sw_on[{max(len(ss.switch_input), 1)}];        /* a forest's machine state: on (> 0.5) */
    int sw_changed[{max(len(ss.switch_input), 1)}];   /* 1: it changed in this campaign */
    double sw_t0[{max(len(ss.switch_input), 1)}];     /* ... at this time, its last change */
    double lstm_h[{_lstm_dims(ss)}];   /* an lstm's hidden state per net and layer */
    double lstm_c[{_lstm_dims(ss)}];   /* ... and its cell state (0 at a campaign's start) */
    double factor[TC_N_LAWS];                   /* each law's factor in this campaign (ATI) */
    double bound[TC_N_SETS][TC_N_OUTPUTS];      /* limit of what the clamp takes out: the last
                                                   sample out of the envelope's (per law set) */
    double t;                                   /* previous sample time, s */
    double t_grid;                              /* the last sample the model stepped on, s */
    double t_read;                              /* last good time read, s */
    double shift;                               /* time read - the stream's clock, s */
    double t_back;                              /* the previous row's time where it was not
                                                   after t_read (NAN: none), s */
    double out[TC_N_OUTPUTS];                   /* previous guarded output (guard, reference) */
    double bias[TC_N_OUTPUTS];                  /* learned from reference measurements */
    double var[TC_N_OUTPUTS];                   /* the bias's variance (TC_ADAPT 1) */
    double gain[TC_N_OUTPUTS];                  /* learned gain (TC_ADAPT 2) */
    double cov[TC_N_OUTPUTS][2][2];             /* covariance of (gain, bias) (TC_ADAPT 2) */
    double c[TC_N_OUTPUTS];                     /* the last corrections given (0 at a campaign's start) */
    int refused;                                /* 1: the last sample was refused (an input not finite) */
    double u_last[TC_N_INPUTS];                 /* (dup99) the inputs of the last sample stepped on */
    int repeated;                               /* 1: the last sample was a row written again, skipped */
    long n_repeated;                            /* ... in this campaign (TC_SKIP_REPEATS) */
{monitor_state(ss)}}} tc_state;

static const char *const TC_INPUT_NAMES[TC_N_INPUTS] = {{{names}}};
/* 1: a signal a diagnosed effect reads, whose missing value (NAN) tc_step holds */
static const int TC_INPUT_HELD[TC_N_INPUTS] = {{{", ".join(str(int(h)) for h in ss.held or [0] * n)}}};
/* the largest |value| a sensor of each input reads (a temperature: 10000 degC); beyond it (a
   logger's overload mark, +9.9E+37 for an open thermocouple) tc_step takes it as NAN, missing */
static const double TC_INPUT_LIMIT[TC_N_INPUTS] = {{{", ".join(number(v) for v in ss.limits)}}};
static const char *const TC_OUTPUT_NAMES[TC_N_OUTPUTS] = {{{outs}}};
static const char *const TC_ERROR_NAMES[TC_N_OUTPUTS] = {{{errors}}};  /* measured errors */
{_derived_references(ss)}
/* The headers of the data the model was made from, which a stream may use instead */
{_lab_names(ss)}

/* The compensator as exported (what was learned: as served), and a campaign starts. */
void tc_init(tc_state *s);

/* Start a campaign (the next sample is the reference); what was learned is kept. */
void tc_reset(tc_state *s);

/* The campaign's initial ambient A0 (degC: its ambient_c in the manifest campaigns.csv) where
   the model reads no ambient sensor (TC_AMBIENT_GIVEN 1; else not read): call it after tc_init
   or tc_reset, before the campaign's first tc_step, which refuses the sample (-1) without it.
   A0 picks the laws of the campaign (an ATI model's interval) as the served model's reset does;
   tc_reset forgets it. */
void tc_set_ambient(tc_state *s, double ambient_c);

/* One sample: raw inputs u (order TC_INPUT_NAMES), its time in s (NAN: one period after the
   previous one) -> corrections c (um, order TC_OUTPUT_NAMES).  Returns the number of inputs
   clamped to the training envelope, or -1 when an input is not measured (not finite, a sensor
   dropout, or beyond its TC_INPUT_LIMIT, an overload mark; a held one is held; with TC_MONITOR
   a monitored one is the sensor monitor's, rebuilt from the others, and refused only where it
   cannot be, mon_rule saying why): the sample is refused, nothing remembered changes and c
   holds the last corrections given (0 before a campaign's first sample), as the plain stream
   refuses such a row. */
int tc_step(tc_state *s, const double u[TC_N_INPUTS], double time, double c[TC_N_OUTPUTS]);

/* A reference measurement of the error (um, order TC_ERROR_NAMES; NAN: not measured) at the
   sample of the last tc_step: updates the bias (and gain) of the next corrections (TC_ADAPT; else,
   or after a refused sample, nothing).  Returns the number of targets updated. */
int tc_reference(tc_state *s, const double measured_error[TC_N_OUTPUTS]);

#endif
"""


def source(ss: StateSpace) -> str:
    n, taps, k, p = len(ss.inputs), len(ss.fir), len(ss.taus), len(ss.powers)
    q = len(ss.derived) + len(ss.initial)
    qi = len(ss.initial)
    d, r = ss.depth, len(ss.laws)
    consts = "\n".join([
        _array("FIR", ss.fir, (taps, n)), _array("REFERENCED", ss.referenced, (n,)),
        _array("LO", ss.lo or [0.0] * n, (n,)), _array("HI", ss.hi or [0.0] * n, (n,)),
        _array("TAU", ss.taus, (k,)),
        _ints("LAG_INPUT", ss.lag_input), _ints("LAG_REST", ss.lag_rest or [0] * k),
        _ints("LAG_OF", ss.lag_of or [-1] * k),
        _array("INTERCEPT", ss.intercept, (r,)), _array("B0", ss.b0, (r, n + p + q)),
        _ints("LAW_TARGET", ss.laws), _ints("LAW_SET", ss.law_set or [0] * r),
        _array("LAW_LO", ss.law_lo or [-UNBOUNDED] * r, (r,)),
        _array("LAW_HI", ss.law_hi or [UNBOUNDED] * r, (r,)),
        _ints("LAW_AMBIENT", ss.law_ambient or [0] * r), _ints("AMBIENT_INPUT", ss.ambient_inputs),
        f"static const double AMBIENT_CENTRE = {number(ss.ambient_centre)};",
        f"static const double AMBIENT_COUNT = {number(max(len(ss.ambient_inputs), 1))};",
        _ints("POWER_SRC", [q[0] for q in ss.powers]),
        _array("POWER_SCALE", [q[1] for q in ss.powers], (p,)),
        _array("POWER_EXP", [q[2] for q in ss.powers], (p,)),
        *(_ints(f"DERIVED_{name}", [f[i] for f in ss.derived])
          for i, name in enumerate(("A", "B", "REF_A", "REF_B"))),
        _ints("DERIVED_CLAMPED", ss.derived_clamped or [0] * len(ss.derived)),
        _ints("DERIVED_OVER", ss.derived_over or [-1] * len(ss.derived)),
        _ints("STATE_INPUT", [st[0] for st in ss.clamp_states]),
        _ints("STATE_REF", [st[1] for st in ss.clamp_states]),
        _array("STATE_GAIN", ss.clamp_state_gain or [[[0.0] * n]] * r,
               (r, len(ss.clamp_states), n)),
        _ints("STATE_FIRST", ss.clamp_state_first or [0] * len(ss.targets)),
        _array("INITIAL_TAU", [f[0] for f in ss.initial], (qi,)),
        _array("INITIAL_W", [_spread(f[1], f[2], n) for f in ss.initial], (qi, n)),
        _array("INITIAL_SENSOR", [_spread(f[1], [1.0] * len(f[1]), n) for f in ss.initial], (qi, n)),
        _array("BD", ss.bd, (r, d, n)), _array("G", ss.g, (r, k)), _array("AR", ss.ar, (r,)),
        _array("CLAMP_GAIN", ss.clamp_gain or [[0.0] * n] * r, (r, n)),
        _ints("CLAMP_OUTRIGHT", ss.clamp_outright or [0] * len(ss.targets)),
        _ints("CLAMP_SPREAD", ss.clamp_spread or [0] * len(ss.targets)),
        *_forest_constants(ss),
        *_lstm_constants(ss),
        *_pattern_constants(ss),
        f"static const int CLAMP = {int(ss.clamp)};",
        *_output_constants(ss), *_declared(monitor_arrays(ss))])
    return f"""{banner(ss, "/*", " *", " */")}
#include <math.h>
#include "compensator.h"

{consts}

void tc_reset(tc_state *s) {{
    int i;
    s->first = 1;
    s->refused = 0;
    s->repeated = 0;
    s->n_repeated = 0;
    s->ambient_c = NAN;
    for (i = 0; i < TC_N_OUTPUTS; i++) s->c[i] = 0.0;
}}

void tc_set_ambient(tc_state *s, double ambient_c) {{ s->ambient_c = ambient_c; }}

void tc_init(tc_state *s) {{
    int i;
    for (i = 0; i < TC_N_OUTPUTS; i++) {{
        s->bias[i] = BIAS0[i];
        s->var[i] = VAR0[i];
        s->gain[i] = GAIN0[i];
        s->cov[i][0][0] = COV0[i][0][0];
        s->cov[i][0][1] = COV0[i][0][1];
        s->cov[i][1][0] = COV0[i][1][0];
        s->cov[i][1][1] = COV0[i][1][1];
        s->out[i] = 0.0;
    }}
    tc_reset(s);
}}

/* 1 when the referenced inputs x leave the training pattern: their scaled, centred residual off
   the pattern's basis exceeds the largest of a training sample */
static int off_pattern(const double x[]) {{
    double z[TC_N_INPUTS], r[TC_N_INPUTS], p, r2 = 0.0;
    int j, k;
    for (j = 0; j < TC_N_INPUTS; j++) r[j] = z[j] = (x[j] - PATTERN_MEAN[j]) / PATTERN_SCALE[j];
    for (k = 0; k < PATTERN_RANK; k++) {{
        p = 0.0;
        for (j = 0; j < TC_N_INPUTS; j++) p += PATTERN_BASIS[j][k] * z[j];
        for (j = 0; j < TC_N_INPUTS; j++) r[j] -= p * PATTERN_BASIS[j][k];
    }}
    for (j = 0; j < TC_N_INPUTS; j++) r2 += r[j] * r[j];
    return r2 > PATTERN_TOL * PATTERN_TOL;
}}

/* an arx_rf model's forests on its machine states' switching, each times its weight and its ARX's
   law's factor (an ATI interval's: 0 outside it, the forest not walked) added to its
   target's output y: per tau a state's ramp expit(k (t - t0) / tau) from its last change t0 (k
   +1 on, -1 off; before its first change the state, 0 or 1), cast to float as scikit-learn's
   trees compare it with their thresholds; each tree walked from its root to a leaf (at most
   TC_TREE_DEPTH steps), a forest the mean of its trees' leaves; a fallback model's forest
   (cmon91: its law's LAW_SET) only while its set is served, as its laws */
static void forests(tc_state *s, const double v[], double t, double y[], int serving) {{
    float f32[{max(len(ss.switch_feature), 1)}];
    int l, r, d, node;
    for (l = 0; l < TC_N_SWITCHES; l++) {{
        int on = SWITCH_INPUT[l] >= 0 && v[SWITCH_INPUT[l]] > 0.5;
        if (s->first) s->sw_changed[l] = 0;
        else if (on != s->sw_on[l]) s->sw_t0[l] = t, s->sw_changed[l] = 1;
        s->sw_on[l] = on;
    }}
    for (l = 0; l < TC_N_FEATURES; l++) {{
        int w = FEATURE_SWITCH[l];
        double f = s->sw_on[w];
        if (s->sw_changed[w]) f = 1.0 / (1.0 + exp(-((s->sw_on[w] ? 1.0 : -1.0) * (t - s->sw_t0[w])
                                                       / FEATURE_TAU[l])));
        f32[l] = (float)f;
    }}
    for (l = 0; l < TC_N_FORESTS; l++) {{
        double sum = 0.0, factor = s->factor[FOREST_LAW[l]];
        if (factor == 0.0 || LAW_SET[FOREST_LAW[l]] != serving) continue;
        for (r = FOREST_TREES[l]; r < FOREST_TREES[l + 1]; r++) {{
            node = TREE_ROOT[r];
            for (d = 0; d < TC_TREE_DEPTH && NODE_LEFT[node] >= 0; d++)
                node = f32[NODE_FEATURE[node]] <= NODE_THRESHOLD[node] ? NODE_LEFT[node] : NODE_RIGHT[node];
            sum += NODE_VALUE[node];
        }}
        y[FOREST_TARGET[l]] += FOREST_WEIGHT[l] * factor * (sum / (FOREST_TREES[l + 1] - FOREST_TREES[l]));
    }}
}}

static double sigmoid(double a) {{ return 1.0 / (1.0 + exp(-a)); }}

/* an lstm model's network, its residual times its weight and its skip law's factor (an ATI
   interval's: 0 outside it, the net not stepped) added to its target's output y: its inputs
   the features the laws read (LSTM_IN: x[.][q], or the lag q - TC_WIDTH), clamped (channel 0
   minus the excess channel 1: it has no step gain, the stream runs it on the clamped inputs
   alone), each times its law's factor (LSTM_IN_LAW: 1, A0 - centre, [A0 > A_thr]),
   standardised; per layer the gates a = W_ih in + b_ih + W_hh h +
   b_hh (torch's rows i, f, g, o), c = f c + i g, h = o tanh(c), in double as the model infers;
   the read-out of the last layer's h times the model's output scale */
static void lstms(tc_state *s, const double x[2][TC_WIDTH], double y[], int serving) {{
    double in[{max(ss.lstm_width, 1)}], a[{max(4 * ss.lstm_hidden, 1)}], out;
    int k, l, r, j;
    for (k = 0; k < TC_N_LSTM; k++) {{
        double factor = s->factor[LSTM_LAW[k]];
        if (factor == 0.0) continue;
        for (j = 0; j < TC_LSTM_WIDTH; j++) in[j] = 0.0;
        for (j = 0; j < TC_LSTM_INPUTS; j++) {{
            int q = LSTM_IN[k][j];
            double xj = q < 0 ? 0.0 : q < TC_WIDTH ? x[0][q] - x[1][q]
                        : s->z[0][q - TC_WIDTH] - s->z[1][q - TC_WIDTH];
            in[j] = (xj * s->factor[LSTM_IN_LAW[k][j]] - LSTM_X_MEAN[k][j]) / LSTM_X_SCALE[k][j];
        }}
        for (l = 0; l < TC_LSTM_LAYERS; l++) {{
            double *h = s->lstm_h[k][l], *c = s->lstm_c[k][l];
            if (s->first)
                for (j = 0; j < TC_LSTM_HIDDEN; j++) h[j] = c[j] = 0.0;
            for (r = 0; r < 4 * TC_LSTM_HIDDEN; r++) {{
                double ih = 0.0, hh = 0.0;
                for (j = 0; j < TC_LSTM_WIDTH; j++) ih += LSTM_W_IH[k][l][r][j] * in[j];
                for (j = 0; j < TC_LSTM_HIDDEN; j++) hh += LSTM_W_HH[k][l][r][j] * h[j];
                a[r] = ih + LSTM_B_IH[k][l][r] + hh + LSTM_B_HH[k][l][r];
            }}
            for (j = 0; j < TC_LSTM_HIDDEN; j++) {{
                int H = TC_LSTM_HIDDEN;
                c[j] = sigmoid(a[H + j]) * c[j] + sigmoid(a[j]) * tanh(a[2 * H + j]);
                h[j] = sigmoid(a[3 * H + j]) * tanh(c[j]);
                in[j] = h[j];
            }}
            for (j = TC_LSTM_HIDDEN; j < TC_LSTM_WIDTH; j++) in[j] = 0.0;
        }}
        out = LSTM_HEAD_BIAS[k];
        for (j = 0; j < TC_LSTM_HIDDEN; j++) out += LSTM_HEAD[k][j] * in[j];   /* the last layer's h */
        if (LAW_SET[LSTM_LAW[k]] == serving)   /* (cmon83: a fallback model's net, while served) */
            y[LSTM_TARGET[k]] += LSTM_WEIGHT[k] * factor * (LSTM_Y_SCALE[k] * out);
    }}
}}

/* a raw value a sensor reads: within its input's limit (NAN, an infinity and a temperature's
   overload mark are not: missing, as the Simulator's StateSpace.measured) */
static int measured(const double u[TC_N_INPUTS], int j) {{ return fabs(u[j]) <= TC_INPUT_LIMIT[j]; }}
{MONITOR_FUNCTIONS}
/* the correction of output i from the model's y: the guard (within the rate limit of the
   previous output over a step or one training period, whichever is longer, then the bound
   widened by allow), then the reference update's gain and bias */
static double corrected(tc_state *s, int i, double y, double dt, double allow) {{
    if (TC_GUARD) {{
        if (!s->first) {{
            double step = (isfinite(dt) && dt > GUARD_PERIOD) ? dt : GUARD_PERIOD;
            double lim = GUARD_RATE[i] * step, d = y - s->out[i];
            if (d > lim) y = s->out[i] + lim;
            else if (d < -lim) y = s->out[i] - lim;
        }}
        /* (cmon82b) a new thermal state declared by the monitor: its bound */
        double lo = TC_MONITOR && s->mon_novel ? GUARD_LO_NEW[i] : GUARD_LO[i];
        double hi = TC_MONITOR && s->mon_novel ? GUARD_HI_NEW[i] : GUARD_HI[i];
        if (y < lo - allow) y = lo - allow;
        else if (y > hi + allow) y = hi + allow;
    }}
    s->out[i] = y;
    return s->c[i] = TC_ADAPT ? -(s->gain[i] * y + s->bias[i]) : -y;
}}

int tc_step(tc_state *s, const double u[TC_N_INPUTS], double time, double c[TC_N_OUTPUTS]) {{
    double uu[TC_N_INPUTS];                 /* u, a held signal's missing value filled */
    double um[TC_N_INPUTS];                 /* u, the monitored inputs as the model reads them */
    double v[TC_N_INPUTS], x[2][TC_WIDTH], xl[2][{max(k, 1)}], ych[2];
    double ysum[2][TC_N_OUTPUTS], excess[TC_N_SETS][TC_N_OUTPUTS];
    double allow[TC_N_OUTPUTS], yout[TC_N_OUTPUTS];
    double dt, now, lag_dt;
    int i, j, l, h, r, clamped = 0, between = 0, serving = 0;
    tc_state committed;
{C_REPEAT_RULE}    /* an input not measured refuses the sample before anything is remembered: one NaN would
       otherwise stay in the lags, the AR feedback and the guard to the campaign's end; so does
       a campaign's first sample without its given ambient (TC_AMBIENT_GIVEN) */
    s->refused = TC_AMBIENT_GIVEN && !TC_AMBIENT_OPTIONAL && s->first && !isfinite(s->ambient_c);
    for (j = 0; j < TC_N_INPUTS; j++)   /* (a monitored one: the monitor's, cdrop77) */
        if (!TC_INPUT_HELD[j] && !measured(u, j) && !(TC_MONITOR && mon_watched(j))) s->refused = 1;
    if (TC_MONITOR && !s->refused && mon_refuses(s, u)) s->refused = 1;
    if (s->refused) {{
        for (i = 0; i < TC_N_OUTPUTS; i++) c[i] = s->c[i];
        return -1;
    }}
    for (j = 0; j < TC_N_INPUTS; j++) s->u_last[j] = u[j];   /* (dup99) as read */
{C_TIME_RULE}    /* the sensor monitor (TC_MONITOR): the monitored inputs as the model reads them */
    if (TC_MONITOR) {{   /* (a monitored reading not measured: missing, NAN) */
        for (j = 0; j < TC_N_INPUTS; j++) um[j] = (measured(u, j) || !mon_watched(j)) ? u[j] : NAN;
        monitor_step(s, um, dt, now);
        u = um;
        serving = mon_serving(s);   /* (cmon83) the law set served: a fallback model's, or 0 */
    }}
    /* a missing signal of derived inputs only (TC_INPUT_HELD) is held at the campaign's
       last value, 0 before any (its derived inputs 0), as the diagnosed model holds it */
    for (j = 0; j < TC_N_INPUTS; j++) {{
        if (s->first) s->seen[j] = 0;
        if (measured(u, j)) s->last[j] = u[j];
        uu[j] = measured(u, j) ? u[j] : (s->seen[j] ? s->last[j] : 0.0);
    }}
    /* causal FIR denoiser */
    for (l = TC_TAPS - 1; l >= 0; l--)
        for (j = 0; j < TC_N_INPUTS; j++)
            s->buf[l][j] = (s->first || l == 0) ? uu[j] : s->buf[l - 1][j];
    /* the training grid (cadence72, timerule.on_grid): the model's memory steps by the time
       since the last sample it stepped on; a sample of a faster stream (a step of at most half
       GRID_PERIOD) less than a period after it (the one nearest a period on is stepped) is
       answered by the model's step from that one's state, which is kept (between73) */
    lag_dt = dt;
    if (GRID_PERIOD > 0.0 && !s->first) {{
        lag_dt = now - s->t_grid;
        between = dt > 0.0 && dt <= GRID_PERIOD / 2 && lag_dt + dt / 2 < GRID_PERIOD;
        if (between) committed = *s;
    }}
    s->t_grid = now;
    for (j = 0; j < TC_N_INPUTS; j++) {{
        v[j] = 0.0;
        for (l = 0; l < TC_TAPS; l++) v[j] += s->buf[l][j] * FIR[l][j];
        if (s->first) s->ref[j] = REFERENCED[j] != 0.0 ? v[j] : 0.0;
        x[0][j] = v[j] - s->ref[j];
        /* envelope (static limit): channel 1 is the excess over the bound */
        x[1][j] = 0.0;
        if (CLAMP && (x[0][j] < LO[j] || x[0][j] > HI[j])) {{
            x[1][j] = x[0][j] - (x[0][j] < LO[j] ? LO[j] : HI[j]);
            clamped++;
        }}
    }}
    if (s->first) {{   /* the campaign's laws: by its initial ambient, the mean of the ambient inputs */
        double a0 = 0.0;
        for (l = 0; l < TC_N_AMBIENT; l++) a0 += v[AMBIENT_INPUT[l]];
        a0 /= AMBIENT_COUNT;
        if (TC_AMBIENT_GIVEN) a0 = s->ambient_c;   /* no sensor: the campaign's, given */
        s->a0 = a0;   /* (NAN where optional and not given: no law reads it, the transients
                         take the mean of their sensors' first values) */
        if (!isfinite(a0)) a0 = 0.0;
        s->t0 = now;
        for (r = 0; r < TC_N_LAWS; r++) {{   /* times (A0 - centre)^LAW_AMBIENT[r]: 0, 1 or 2 */
            s->factor[r] = (a0 > LAW_LO[r] && a0 <= LAW_HI[r]) ? 1.0 : 0.0;
            for (l = 0; l < LAW_AMBIENT[r]; l++) s->factor[r] *= a0 - AMBIENT_CENTRE;
        }}
    }}
    if (clamped && PATTERN && !off_pattern(x[0])) {{   /* along the training pattern: passed */
        for (j = 0; j < TC_N_INPUTS; j++) x[1][j] = 0.0;
        clamped = 0;
    }}
    /* static powers of machine states (Hammerstein): sign(w) |w|^e, w = v / scale */
    for (l = 0; l < TC_N_POWERS; l++) {{
        double w = v[POWER_SRC[l]] / POWER_SCALE[l];
        x[0][TC_N_INPUTS + l] = w < 0.0 ? -pow(-w, POWER_EXP[l]) : pow(w, POWER_EXP[l]);
        x[1][TC_N_INPUTS + l] = 0.0;
    }}
    /* a diagnosed model's derived inputs: r_a r_b (b < 0: r_a), r_j = v_j - its first value
       where REF (the effect's frame), 0 before any, as the stream's model reads its context */
    for (j = 0; j < TC_N_INPUTS; j++)
        if (!s->seen[j] && measured(u, j)) {{
            s->v0[j] = v[j];
            s->seen[j] = 1;
        }}
    if (s->first)   /* the model's inputs and their excess at its first sample */
        for (j = 0; j < TC_N_INPUTS; j++) s->x0[0][j] = x[0][j], s->x0[1][j] = x[1][j];
    for (l = 0; l < TC_N_DERIVED; l++) {{
        int a = DERIVED_A[l], b = DERIVED_B[l], c = DERIVED_OVER[l];
        double ra = s->seen[a] ? v[a] - (DERIVED_REF_A[l] ? s->v0[a] : 0.0) : 0.0;
        double rb = b < 0 ? 1.0 : (s->seen[b] ? v[b] - (DERIVED_REF_B[l] ? s->v0[b] : 0.0) : 0.0);
        if (c >= 0 && s->seen[c])   /* a rise over the air's: r_b - r_c, in r_b's frame */
            rb -= v[c] - (DERIVED_REF_B[l] ? s->v0[c] : 0.0);
        if (DERIVED_CLAMPED[l]) {{   /* a state times the model input's rise, clamped in channel 1 */
            x[0][TC_N_INPUTS + TC_N_POWERS + l] = ra * (x[0][b] - s->x0[0][b]);
            x[1][TC_N_INPUTS + TC_N_POWERS + l] = ra * (x[1][b] - s->x0[1][b]);
        }} else {{
            x[0][TC_N_INPUTS + TC_N_POWERS + l] = ra * rb;
            x[1][TC_N_INPUTS + TC_N_POWERS + l] = 0.0;
        }}
    }}
    /* the clamp's gain grows by a state's value times its inputs_product's gain: the value of
       the sample before the campaign's first excess, held (out at its first sample: no value,
       the target clamped outright), as the stream forks its clamped copy then */
    if (s->first) {{
        s->excessed = 0;
        for (i = 0; i < TC_N_OUTPUTS; i++) s->by_outright[i] = 0;
        for (l = 0; l < TC_N_STATE_GAIN; l++) s->by_held[l] = 0.0;
    }}
    if (TC_N_STATE_GAIN && clamped && !s->excessed) {{
        s->excessed = 1;
        for (i = 0; i < TC_N_OUTPUTS && s->first; i++) s->by_outright[i] = STATE_FIRST[i];
        for (l = 0; l < TC_N_STATE_GAIN && !s->first; l++) s->by_held[l] = s->by_prev[l];
    }}
    for (l = 0; l < TC_N_STATE_GAIN; l++) {{
        int a = STATE_INPUT[l];
        s->by_prev[l] = s->seen[a] ? v[a] - (STATE_REF[l] ? s->v0[a] : 0.0) : 0.0;
    }}
    /* a diagnosed lag's initial-state transient: w . (c(0) - A0) (1 - exp(-(t - t0) / tau)), c(0)
       its sensors at the campaign's first sample that has one of them (a missing one: 0, its
       offset unknown), 0 before it, as the stream's model computes it */
    for (l = 0; l < TC_N_INITIAL; l++) {{
        int col = TC_N_INPUTS + TC_N_POWERS + TC_N_DERIVED + l, any = 0;
        double start = 0.0, ref = s->a0, seen = 0.0;
        if (s->first) s->started[l] = 0, s->start[l] = 0.0;
        if (!isfinite(ref)) {{   /* A0 not given (TC_AMBIENT_OPTIONAL): its sensors' mean */
            ref = 0.0;
            for (j = 0; j < TC_N_INPUTS; j++)
                if (INITIAL_SENSOR[l][j] != 0.0 && measured(u, j)) ref += v[j], seen += 1.0;
            ref = seen > 0.0 ? ref / seen : 0.0;
        }}
        for (j = 0; j < TC_N_INPUTS && !s->started[l]; j++)
            if (INITIAL_SENSOR[l][j] != 0.0 && measured(u, j)) {{
                start += INITIAL_W[l][j] * (v[j] - ref);
                any = 1;
            }}
        if (any) s->start[l] = start, s->started[l] = 1;
        x[0][col] = s->start[l] * (1.0 - exp(-(now - s->t0) / INITIAL_TAU[l]));
        x[1][col] = 0.0;
    }}
    /* first-order lags */
    for (h = 0; h < 2; h++)
        for (l = 0; l < TC_N_LAGS; l++) {{
            /* a cascade (LAG_OF: a lag of a lag, after it) lags that lag's new value */
            xl[h][l] = LAG_OF[l] >= 0 ? s->z[h][LAG_OF[l]] : x[h][LAG_INPUT[l]];
            if (s->first) {{   /* a machine state at rest (Hammerstein) starts at 0 */
                s->z[h][l] = LAG_REST[l] ? 0.0 : xl[h][l];
            }} else {{
                double e = exp(-lag_dt / TAU[l]);
                s->z[h][l] = e * s->z[h][l] + (1.0 - e) * xl[h][l];
            }}
        }}
    if (s->first) {{
        for (h = 0; h < 2; h++) {{
            for (l = 0; l < TC_DEPTH; l++)
                for (j = 0; j < TC_N_INPUTS; j++) s->hist[h][l][j] = x[h][j];
            for (r = 0; r < TC_N_LAWS; r++) s->y[h][r] = 0.0;
        }}
    }}
    s->t = now;
    /* the guard's bound widens by the response to the inputs beyond their training range, at a
       sample on the training pattern (a hotter machine; one sensor leaving the others: not) */
    for (i = 0; i < TC_N_OUTPUTS; i++) allow[i] = 0.0;
    if (TC_GUARD_INPUTS) {{
        double d[TC_N_INPUTS];
        int beyond = 0;
        for (j = 0; j < TC_N_INPUTS; j++) {{
            d[j] = x[0][j] > GUARD_IN_HI[j] ? x[0][j] - GUARD_IN_HI[j]
                 : (x[0][j] < GUARD_IN_LO[j] ? GUARD_IN_LO[j] - x[0][j] : 0.0);
            if (d[j] > 0.0) beyond = 1;
        }}
        if (beyond && !off_pattern(x[0]))
            for (i = 0; i < TC_N_OUTPUTS; i++)
                for (j = 0; j < TC_N_INPUTS; j++) allow[i] += GUARD_GAIN[i][j] * d[j];
    }}
    /* outputs: static part, input history, lags, AR feedback; the response to the excess is
       taken out up to the response to it held for the envelope's horizon; back in range, up to
       the last excess's (the memory of an excess that ends at once is taken out as it decays) */
    for (i = 0; i < TC_N_OUTPUTS; i++) ysum[0][i] = ysum[1][i] = 0.0;
    for (h = 0; h < TC_N_SETS; h++)
        for (i = 0; i < TC_N_OUTPUTS; i++) excess[h][i] = 0.0;
    /* each law (its own feedback) steps, summed into its target where its set is served
       (LAW_SET: a fallback model's laws step beside the model's from the campaign's start) */
    for (r = 0; r < TC_N_LAWS; r++) {{
        double p = 0.0;
        for (j = 0; j < TC_N_INPUTS; j++) {{
            double gain = CLAMP_GAIN[r][j];
            for (l = 0; l < TC_N_STATE_GAIN; l++) gain += s->by_held[l] * STATE_GAIN[r][l][j];
            p += gain * x[1][j];
        }}
        if (s->factor[r] != 0.0) excess[LAW_SET[r]][LAW_TARGET[r]] += s->factor[r] * p;
        for (h = 0; h < 2; h++) {{
            ych[h] = h == 0 ? INTERCEPT[r] : 0.0;
            for (j = 0; j < TC_WIDTH; j++) ych[h] += B0[r][j] * x[h][j];
            for (l = 0; l < TC_DEPTH; l++)
                for (j = 0; j < TC_N_INPUTS; j++) ych[h] += BD[r][l][j] * s->hist[h][l][j];
            for (l = 0; l < TC_N_LAGS; l++) ych[h] += G[r][l] * (s->z[h][l] - xl[h][l]);
            ych[h] += AR[r] * s->y[h][r];
            s->y[h][r] = ych[h];
            if (s->factor[r] != 0.0 && LAW_SET[r] == serving)
                ysum[h][LAW_TARGET[r]] += s->factor[r] * ych[h];
        }}
    }}
    if (TC_N_FORESTS) forests(s, v, TC_SWITCH_RAW_TIME ? time : now, ysum[0], serving);
    if (TC_N_LSTM) lstms(s, (const double (*)[TC_WIDTH])x, ysum[0], serving);
    for (i = 0; i < TC_N_OUTPUTS; i++) {{
        double bound = 0.0;
        ych[0] = ysum[0][i];
        ych[1] = ysum[1][i];
        for (h = 0; h < TC_N_SETS && (s->first || clamped); h++) s->bound[h][i] = fabs(excess[h][i]);
        /* outright: no step gain (or none yet: a state's, out at the campaign's first sample) */
        bound = (CLAMP_OUTRIGHT[i] || s->by_outright[i]) ? HUGE_VAL : s->bound[serving][i];
        /* a white target at a sample whose excess two inputs or more share: a heat source's */
        if (CLAMP_SPREAD[i] && clamped >= 2) bound = 0.0;
        yout[i] = ych[0] - (ych[1] > bound ? bound : (ych[1] < -bound ? -bound : ych[1]));
    }}
    for (h = 0; h < 2; h++)
        for (l = TC_DEPTH - 1; l >= 0; l--)
            for (j = 0; j < TC_N_INPUTS; j++)
                s->hist[h][l][j] = l == 0 ? x[h][j] : s->hist[h][l - 1][j];
    if (between) {{   /* the model's state back to the grid sample's; the time, the guard go on */
        *s = committed;
        s->t = now;
    }}
    for (i = 0; i < TC_N_OUTPUTS; i++) c[i] = corrected(s, i, yout[i], dt, allow[i]);
    s->first = 0;
    return clamped;
}}

static double clip(double v, double lo, double hi) {{ return v < lo ? lo : (v > hi ? hi : v); }}

/* (gain, bias) of target i by recursive least squares on phi = (y, 1) */
static void rls(tc_state *s, int i, double e) {{
    double y = s->out[i], (*P)[2] = s->cov[i], trace;
    double pp0 = P[0][0] * y + P[0][1], pp1 = P[1][0] * y + P[1][1];    /* P phi */
    double q0 = y * P[0][0] + P[1][0], q1 = y * P[0][1] + P[1][1];      /* phi' P */
    double den = FORGETTING + (q0 * y + q1);
    double k0 = pp0 / den, k1 = pp1 / den, err = e - (y * s->gain[i] + s->bias[i]);
    double g = s->gain[i] + k0 * err, b = s->bias[i] + k1 * err;
    P[0][0] = (P[0][0] - k0 * q0) / FORGETTING;
    P[0][1] = (P[0][1] - k0 * q1) / FORGETTING;
    P[1][0] = (P[1][0] - k1 * q0) / FORGETTING;
    P[1][1] = (P[1][1] - k1 * q1) / FORGETTING;
    trace = P[0][0] + P[1][1];
    if (VAR_CAP > 0.0 && trace / VAR_CAP > 1.0) {{
        double by = trace / VAR_CAP;
        P[0][0] /= by; P[0][1] /= by; P[1][0] /= by; P[1][1] /= by;
    }}
    s->gain[i] = clip(g, 1.0 - MAX_GAIN_CHANGE, 1.0 + MAX_GAIN_CHANGE);
    s->bias[i] = clip(b, -MAX_BIAS, MAX_BIAS);
}}

int tc_reference(tc_state *s, const double measured_error[TC_N_OUTPUTS]) {{
    int i, n = 0;
    if (!TC_ADAPT || s->refused) return 0;   /* nothing was predicted at a refused sample */
    /* the bounded recursive filter (forgetting, covariance capped at its prior) */
    for (i = 0; i < TC_N_OUTPUTS; i++) {{
        double p = s->var[i], k, b;
        if (!isfinite(measured_error[i])) continue;
        if (TC_ADAPT == 2) {{
            rls(s, i, measured_error[i]);
            n++;
            continue;
        }}
        k = p / (FORGETTING + p);
        b = s->bias[i] + k * (measured_error[i] - s->gain[i] * s->out[i] - s->bias[i]);
        p = (p - k * p) / FORGETTING;
        s->var[i] = (VAR_CAP > 0.0 && p / VAR_CAP > 1.0) ? p / (p / VAR_CAP) : p;
        s->bias[i] = b < -MAX_BIAS ? -MAX_BIAS : (b > MAX_BIAS ? MAX_BIAS : b);
        n++;
    }}
    return n;
}}
"""


def _declared(arrays) -> list[str]:
    """A model's constants (:func:`.forest.forest_arrays`, :func:`.recurrent.net_arrays`) in C."""
    return [_array(name, values, shape) if kind == "real" else
            _ints(name, values) if len(shape) == 1 else _array(name, values, shape, "int")
            for name, values, shape, kind in arrays]   # (a scalar: shape ())


def _forest_constants(ss: StateSpace) -> list[str]:
    """An arx_rf model's forests (:mod:`.forest`): the states, features, trees and nodes."""
    return _declared(forest_arrays(ss))


def _lstm_dims(ss: StateSpace) -> str:
    return "][".join(str(max(d, 1)) for d in (len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden))


def _lstm_constants(ss: StateSpace) -> list[str]:
    """An lstm model's networks (:mod:`.recurrent`): standardisation, gates, read-out."""
    return _declared(net_arrays(ss))


def _output_constants(ss: StateSpace) -> list[str]:
    """The time rule's period, the guard's limits and the reference update's constants (zeros
    where there is none)."""
    m, n = len(ss.targets), len(ss.inputs)
    rate = [math.inf if r is None else r for r in ss.guard_rate or [0.0] * m]
    return [f"static const double TIME_PERIOD = {number(ss.time_period)};",
            f"static const double GRID_PERIOD = {number(ss.grid_period)};",
            _array("GUARD_LO", ss.guard_lo or [0.0] * m, (m,)),
            _array("GUARD_HI", ss.guard_hi or [0.0] * m, (m,)), _array("GUARD_RATE", rate, (m,)),
            f"static const double GUARD_PERIOD = {number(ss.guard_period)};",
            _array("GUARD_LO_NEW", ss.guard_lo_new or ss.guard_lo or [0.0] * m, (m,)),
            _array("GUARD_HI_NEW", ss.guard_hi_new or ss.guard_hi or [0.0] * m, (m,)),
            _array("GUARD_GAIN", ss.guard_gain or [[0.0] * n] * m, (m, n)),
            _array("GUARD_IN_LO", ss.guard_in_lo or [0.0] * n, (n,)),
            _array("GUARD_IN_HI", ss.guard_in_hi or [0.0] * n, (n,)),
            _array("GAIN0", ss.adapt_gain or [1.0] * m, (m,)),
            _array("COV0", ss.adapt_cov or [[[0.0, 0.0], [0.0, 0.0]]] * m, (m, 2, 2)),
            f"static const double MAX_GAIN_CHANGE = {number(ss.adapt_max_gain_change)};",
            _array("BIAS0", ss.adapt_bias or [0.0] * m, (m,)),
            _array("VAR0", ss.adapt_var or [0.0] * m, (m,)),
            f"static const double FORGETTING = {number(ss.adapt_forgetting)};",
            f"static const double MAX_BIAS = {number(ss.adapt_max_bias)};",
            f"static const double VAR_CAP = {number(ss.adapt_var_cap)};"]

