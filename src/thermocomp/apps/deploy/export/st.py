"""The exported system (:class:`~.statespace.StateSpace`) as an IEC 61131-3 Structured Text
function block, ``FB_ThermoComp``, with the interface of the C code: one call is one
``tc_step``; ``reset := TRUE`` is ``tc_reset`` before it (the sample starts a campaign).

Inputs ``u`` (raw values, order of the banner), ``time_s`` and ``has_time`` (FALSE: no time,
:mod:`thermocomp.core.timerule`: ST has no NaN constant), ``ambient_c`` (°C: a campaign's
initial ambient, its manifest ``ambient_c``, read at its first sample where ``AMBIENT_GIVEN``,
a model without an ambient sensor; else not read), ``ref_valid`` and ``ref_error`` (per target: a
reference measurement of the error at this sample, which ``tc_reference`` takes after the
step); outputs ``c`` (µm), ``n_clamped`` and ``refused`` (an input not measured: NaN, infinity, or
beyond its ``U_LIMIT``, a temperature's overload mark; the sample and its reference are not taken
and ``c`` holds, as ``tc_step`` returns -1).  What
was learned from references survives ``reset`` (the instance's initial values are the exported
ones).  Only assignments, ``IF``, ``FOR``, ``EXP``, ``EXPT`` and (an arx_rf model's forest)
``LREAL_TO_REAL``, ``REAL_TO_LREAL`` and ``DINT_TO_LREAL`` are used, one statement a line (an
lstm model's tanh is written with ``EXP``, ``tanh(z) = 1 - 2 / (EXP(2 z) + 1)``, its argument
held within +-20, where tanh is +-1 to double precision, and a sigmoid's within +-80: an EXP
that overflows stops many PLCs).
"""

from __future__ import annotations

from ....core.timerule import ST_REPEAT_RULE, ST_TIME_RULE
from .forest import forest_arrays
from .recurrent import net_arrays, net_inputs
from .st_watch import BLOCK as MONITOR_BLOCK
from .st_watch import OUTPUTS as MONITOR_OUTPUTS
from .st_watch import constants as monitor_constants
from .st_watch import declarations as monitor_declarations
from .statespace import StateSpace
from .text import banner

NAME = "FB_ThermoComp"
LREAL_MAX = 1.7976931348623157e308   # an unlimited rate, the test of a finite input (ST has no infinity)


def literal(v: float) -> str:
    """An LREAL literal (always a decimal point, 17 significant digits: the same double)."""
    return f"{float(v):.16e}"


def _dims(*shape: int) -> str:
    return ", ".join(f"0..{max(d, 1) - 1}" for d in shape)


def _flat(values) -> list:
    if isinstance(values, (list, tuple)):
        return [v for item in values for v in _flat(item)]
    return [values]


def _constant(name: str, values, shape: tuple[int, ...], kind: str = "LREAL") -> str:
    flat = _flat(values) or [0]
    flat += [0] * (max(1, _size(shape)) - len(flat))
    text = ", ".join(literal(v) if kind == "LREAL" else str(int(v)) for v in flat)
    return f"    {name} : ARRAY[{_dims(*shape)}] OF {kind} := [{text}];"


def _size(shape) -> int:
    out = 1
    for d in shape:
        out *= max(d, 1)
    return out


def _indent(code: str) -> str:
    return "".join("    " + line if line.strip() else line for line in code.splitlines(True))


def _spread(columns: list, values: list, n: int) -> list:
    """``values`` at ``columns`` of a row of ``n`` zeros."""
    row = [0.0] * n
    for j, v in zip(columns, values):
        row[j] = v
    return row


ST_KINDS = {"int": "INT", "index": "DINT", "real": "LREAL"}   # an index: more than an INT counts


def _declared(arrays) -> list[str]:
    """A model's constants (:func:`.forest.forest_arrays`, :func:`.recurrent.net_arrays`) in ST."""
    return [_constant(name, values, shape, ST_KINDS[kind]) for name, values, shape, kind in arrays]


def _forest_constants(ss: StateSpace) -> list[str]:
    """An arx_rf model's forests (:mod:`.forest`): node indices DINT (a forest of a hundred trees
    has more nodes than an INT counts)."""
    return [f"    N_SWITCHES : INT := {len(ss.switch_input)};",
            f"    N_FEATURES : INT := {len(ss.switch_feature)};",
            f"    N_FORESTS : INT := {len(ss.forest_target)};",
            f"    TREE_DEPTH : INT := {ss.tree_depth};",
            f"    SWITCH_RAW_TIME : BOOL := {'TRUE' if ss.switch_raw_time else 'FALSE'};",
            *_declared(forest_arrays(ss))]


def _lstm_constants(ss: StateSpace) -> list[str]:
    """An lstm model's networks (:mod:`.recurrent`)."""
    x_width = len(ss.inputs) + len(ss.powers) + len(ss.derived) + len(ss.initial)
    return [f"    N_LSTM : INT := {len(ss.lstm_target)};", f"    LSTM_HIDDEN : INT := {ss.lstm_hidden};",
            f"    LSTM_LAYERS : INT := {ss.lstm_layers};", f"    LSTM_WIDTH : INT := {ss.lstm_width};",
            f"    LSTM_INPUTS : INT := {net_inputs(ss)};",
            f"    LSTM_LAG_FROM : INT := {x_width};",     # the nets' sources: x, then the lags
            *_declared(net_arrays(ss))]


LSTM_BLOCK = """\
    (* an lstm model's network, its residual times its weight and its skip law's factor (an ATI *)
    (* interval's: 0 outside it, the net not stepped) added to its target: its inputs the *)
    (* features the laws read (LSTM_IN: x[., q], or the lag q - LSTM_LAG_FROM), clamped *)
    (* (channel 0 minus the excess channel 1: no step gain, the stream runs it on the clamped *)
    (* inputs alone), each times its law's factor (LSTM_IN_LAW: 1, A0 - centre, [A0 > A_thr]), *)
    (* standardised; per layer the gates a = W_ih in + b_ih + W_hh h + b_hh *)
    (* (torch's rows i, f, g, o), c := f c + i g, h := o tanh(c); sigmoid 1 / (1 + EXP(-a)) and *)
    (* tanh(z) = 1 - 2 / (EXP(2 z) + 1), their arguments held where EXP cannot overflow *)
    FOR nk := 0 TO N_LSTM - 1 DO
        lfac := factor[LSTM_LAW[nk]];
        IF lfac <> 0.0 THEN
            FOR j := 0 TO LSTM_WIDTH - 1 DO
                lstm_in[j] := 0.0;
            END_FOR;
            FOR j := 0 TO LSTM_INPUTS - 1 DO
                lq := LSTM_IN[nk, j];
                IF lq < 0 THEN
                    lx := 0.0;
                ELSIF lq < LSTM_LAG_FROM THEN
                    lx := x[0, lq] - x[1, lq];
                ELSE
                    lx := z[0, lq - LSTM_LAG_FROM] - z[1, lq - LSTM_LAG_FROM];
                END_IF;
                lstm_in[j] := (lx * factor[LSTM_IN_LAW[nk, j]] - LSTM_X_MEAN[nk, j]) / LSTM_X_SCALE[nk, j];
            END_FOR;
            FOR nl := 0 TO LSTM_LAYERS - 1 DO
                IF first THEN
                    FOR j := 0 TO LSTM_HIDDEN - 1 DO
                        lstm_h[nk, nl, j] := 0.0;
                        lstm_c[nk, nl, j] := 0.0;
                    END_FOR;
                END_IF;
                FOR nr := 0 TO 4 * LSTM_HIDDEN - 1 DO
                    la := 0.0;
                    lb := 0.0;
                    FOR j := 0 TO LSTM_WIDTH - 1 DO
                        la := la + LSTM_W_IH[nk, nl, nr, j] * lstm_in[j];
                    END_FOR;
                    FOR j := 0 TO LSTM_HIDDEN - 1 DO
                        lb := lb + LSTM_W_HH[nk, nl, nr, j] * lstm_h[nk, nl, j];
                    END_FOR;
                    la := la + LSTM_B_IH[nk, nl, nr] + lb + LSTM_B_HH[nk, nl, nr];
                    IF nr >= 2 * LSTM_HIDDEN AND nr < 3 * LSTM_HIDDEN THEN
                        (* g: tanh *)
                        IF la > 20.0 THEN
                            la := 20.0;
                        ELSIF la < -20.0 THEN
                            la := -20.0;
                        END_IF;
                        lstm_a[nr] := 1.0 - 2.0 / (EXP(2.0 * la) + 1.0);
                    ELSE
                        (* i, f, o: sigmoid *)
                        IF la > 80.0 THEN
                            la := 80.0;
                        ELSIF la < -80.0 THEN
                            la := -80.0;
                        END_IF;
                        lstm_a[nr] := 1.0 / (1.0 + EXP(-la));
                    END_IF;
                END_FOR;
                FOR j := 0 TO LSTM_HIDDEN - 1 DO
                    lg := lstm_a[LSTM_HIDDEN + j] * lstm_c[nk, nl, j];
                    lg := lg + lstm_a[j] * lstm_a[2 * LSTM_HIDDEN + j];
                    lstm_c[nk, nl, j] := lg;
                    IF lg > 20.0 THEN
                        lg := 20.0;
                    ELSIF lg < -20.0 THEN
                        lg := -20.0;
                    END_IF;
                    lstm_h[nk, nl, j] := lstm_a[3 * LSTM_HIDDEN + j] * (1.0 - 2.0 / (EXP(2.0 * lg) + 1.0));
                    lstm_in[j] := lstm_h[nk, nl, j];
                END_FOR;
                FOR j := LSTM_HIDDEN TO LSTM_WIDTH - 1 DO
                    lstm_in[j] := 0.0;
                END_FOR;
            END_FOR;
            lsum := LSTM_HEAD_BIAS[nk];
            FOR j := 0 TO LSTM_HIDDEN - 1 DO
                lsum := lsum + LSTM_HEAD[nk, j] * lstm_in[j];
            END_FOR;
            i := LSTM_TARGET[nk];
            ysum[0, i] := ysum[0, i] + LSTM_WEIGHT[nk] * lfac * (LSTM_Y_SCALE[nk] * lsum);
        END_IF;
    END_FOR;
"""


def _memory(ss: StateSpace) -> list[tuple[str, str, tuple]]:
    """The model's memory a sample between two grid rows steps on a copy of (between73): per
    variable its name, type and shape (``()`` a scalar); what only a campaign's first sample
    sets is not among them (never such a sample)."""
    n, m, k, d, r = len(ss.inputs), len(ss.targets), len(ss.taus), ss.depth, len(ss.laws)
    nb, qi, ns = len(ss.clamp_states), len(ss.initial), len(ss.switch_input)
    cells = (len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden)
    return [("v0", "LREAL", (n,)), ("seen", "BOOL", (n,)), ("by_prev", "LREAL", (nb,)),
            ("by_held", "LREAL", (nb,)), ("excessed", "BOOL", ()), ("by_outright", "BOOL", (m,)),
            ("init_start", "LREAL", (qi,)), ("init_started", "BOOL", (qi,)),
            ("hist", "LREAL", (2, d, n)), ("z", "LREAL", (2, k)), ("y_prev", "LREAL", (2, r)),
            ("bound_held", "LREAL", (_sets(ss), m)), ("sw_on", "BOOL", (ns,)), ("sw_changed", "BOOL", (ns,)),
            ("sw_t0", "LREAL", (ns,)), ("lstm_h", "LREAL", cells), ("lstm_c", "LREAL", cells)]


def _sets(ss: StateSpace) -> int:
    """The law sets of ``ss``: the model's, and each fallback model's (:mod:`.fallbacks`)."""
    return max(ss.law_set or [0]) + 1


def _served_sets(watch: dict) -> list[int]:
    """(st103b) Per monitored sensor the law set served while the block holds it out: its
    fallback model's (the monitor's ``fallback_set``), 0 where the others left in are too few to
    rebuild the field (the C's ``mon_serving``)."""
    n = len(watch.get("inputs", []))
    return [int(s) if n - 1 >= watch.get("min_active", n) else 0 for s in watch.get("fallback_set", [])]


def _copied(ss: StateSpace, back: bool, indent: str = "        ") -> str:
    """Every variable of :func:`_memory` copied to its ``_kept`` twin, or back (element by
    element: an array assignment is not every PLC's)."""
    lines = []
    for name, _, shape in _memory(ss):
        src, dst = (f"{name}_kept", name) if back else (name, f"{name}_kept")
        if not shape:
            lines.append(f"{indent}{dst} := {src};")
            continue
        index = ("i", "j", "l")[:len(shape)]
        at = ", ".join(index)
        for depth, (v, size) in enumerate(zip(index, shape)):
            lines.append(f"{indent}{'    ' * depth}FOR {v} := 0 TO {max(size, 1) - 1} DO")
        lines.append(f"{indent}{'    ' * len(shape)}{dst}[{at}] := {src}[{at}];")
        lines += [f"{indent}{'    ' * depth}END_FOR;" for depth in reversed(range(len(shape)))]
    return "\n".join(lines)


def function_block(ss: StateSpace, watch: dict | None = None) -> str:
    """``FB_ThermoComp`` of ``ss``; ``watch`` (st93): the adaptive compensator's monitor
    (:func:`.watch.monitor_fields`'s ``monitor``), whose detection the block outputs
    (:mod:`.st_watch`; none: ``MON_N`` 0, never flagged)."""
    watch = watch or {}
    n, m, taps, k, d = len(ss.inputs), len(ss.targets), len(ss.fir), len(ss.taus), ss.depth
    p, r, qi = len(ss.powers), len(ss.laws), len(ss.initial)
    q = len(ss.derived) + qi       # the derived inputs, then the transients' (N_DERIVED first)
    nb = len(ss.clamp_states)      # states whose value scales the clamp's gain (inputs_product)
    sets = _sets(ss)
    consts = "\n".join([
        f"    N_INPUTS : INT := {n};", f"    N_OUTPUTS : INT := {m};", f"    N_LAWS : INT := {r};",
        f"    TAPS : INT := {taps};",
        f"    DEPTH : INT := {d};", f"    N_LAGS : INT := {k};", f"    N_POWERS : INT := {p};",
        f"    N_DERIVED : INT := {len(ss.derived)};",
        f"    N_INITIAL : INT := {qi};",
        f"    CLAMP : BOOL := {'TRUE' if ss.clamp else 'FALSE'};",
        f"    REAL_LIMIT : LREAL := {literal(LREAL_MAX)};",
        _constant("FIR", ss.fir, (taps, n)), _constant("REFERENCED", ss.referenced, (n,)),
        _constant("LO", ss.lo or [], (n,)), _constant("HI", ss.hi or [], (n,)),
        _constant("CLAMP_GAIN", ss.clamp_gain or [], (r, n)),
        _constant("CLAMP_OUTRIGHT", ss.clamp_outright or [], (m,), "INT"),
        _constant("CLAMP_SPREAD", ss.clamp_spread or [], (m,), "INT"),
        f"    PATTERN : BOOL := {'TRUE' if ss.pattern else 'FALSE'};",
        f"    PATTERN_RANK : INT := {len(ss.pattern_basis[0]) if ss.pattern else 0};",
        f"    PATTERN_TOL : LREAL := {literal(ss.pattern_tol)};",
        _constant("PATTERN_MEAN", ss.pattern_mean or [], (n,)),
        _constant("PATTERN_SCALE", ss.pattern_scale or [1.0] * n, (n,)),
        _constant("PATTERN_BASIS", ss.pattern_basis or [],
                  (n, len(ss.pattern_basis[0]) if ss.pattern else 1)),
        _constant("TAU", ss.taus, (k,)),
        _constant("LAG_INPUT", ss.lag_input, (k,), "INT"),
        _constant("LAG_REST", ss.lag_rest or [0] * k, (k,), "INT"),
        _constant("LAG_OF", ss.lag_of or [-1] * k, (k,), "INT"),
        _constant("INTERCEPT", ss.intercept, (r,)), _constant("B0", ss.b0, (r, n + p + q)),
        _constant("LAW_TARGET", ss.laws, (r,), "INT"),
        f"    N_SETS : INT := {sets};", _constant("LAW_SET", ss.law_set or [0] * r, (r,), "INT"),
        _constant("MON_FALLBACK_SET", _served_sets(watch), (len(watch.get("inputs", [])),), "INT"),
        _constant("LAW_LO", ss.law_lo or [-LREAL_MAX] * r, (r,)),
        _constant("LAW_HI", ss.law_hi or [LREAL_MAX] * r, (r,)),
        _constant("LAW_AMBIENT", ss.law_ambient or [0] * r, (r,), "INT"),
        f"    N_AMBIENT : INT := {len(ss.ambient_inputs)};",
        _constant("AMBIENT_INPUT", ss.ambient_inputs, (len(ss.ambient_inputs),), "INT"),
        f"    AMBIENT_CENTRE : LREAL := {literal(ss.ambient_centre)};",
        f"    AMBIENT_COUNT : LREAL := {literal(max(len(ss.ambient_inputs), 1))};",
        f"    AMBIENT_GIVEN : BOOL := {'TRUE' if ss.ambient_given else 'FALSE'};",
        f"    AMBIENT_OPTIONAL : BOOL := {'TRUE' if ss.ambient_optional else 'FALSE'};",
        _constant("POWER_SRC", [q[0] for q in ss.powers], (p,), "INT"),
        _constant("POWER_SCALE", [q[1] for q in ss.powers], (p,)),
        _constant("POWER_EXP", [q[2] for q in ss.powers], (p,)),
        _constant("HELD", ss.held or [], (n,), "INT"),
        _constant("U_LIMIT", ss.limits, (n,)),
        _constant("INITIAL_TAU", [f[0] for f in ss.initial], (qi,)),
        _constant("INITIAL_W", [_spread(f[1], f[2], n) for f in ss.initial], (qi, n)),
        _constant("INITIAL_SENSOR", [_spread(f[1], [1] * len(f[1]), n) for f in ss.initial],
                  (qi, n), "INT"),
        *(_constant(f"DERIVED_{name}", [f[i] for f in ss.derived], (len(ss.derived),), "INT")
          for i, name in enumerate(("A", "B", "REF_A", "REF_B"))),
        _constant("DERIVED_CLAMPED", ss.derived_clamped or [], (len(ss.derived),), "INT"),
        _constant("DERIVED_OVER", ss.derived_over or [-1] * len(ss.derived), (len(ss.derived),),
                  "INT"),
        f"    N_STATE_GAIN : INT := {nb};",
        _constant("STATE_INPUT", [st[0] for st in ss.clamp_states], (nb,), "INT"),
        _constant("STATE_REF", [st[1] for st in ss.clamp_states], (nb,), "INT"),
        _constant("STATE_GAIN", ss.clamp_state_gain or [], (r, nb, n)),
        _constant("STATE_FIRST", ss.clamp_state_first or [], (m,), "INT"),
        _constant("BD", ss.bd, (r, d, n)), _constant("G", ss.g, (r, k)), _constant("AR", ss.ar, (r,)),
        *_forest_constants(ss),
        *_lstm_constants(ss),
        f"    SUBSTITUTE_TIME : BOOL := {'TRUE' if ss.substitute_time else 'FALSE'};",
        f"    SKIP_REPEATS : BOOL := {'TRUE' if ss.skip_repeats else 'FALSE'};",
        f"    TIME_PERIOD : LREAL := {literal(ss.time_period)};",
        f"    GRID_PERIOD : LREAL := {literal(ss.grid_period)};",
        f"    USE_GUARD : BOOL := {'TRUE' if ss.guard else 'FALSE'};",
        _constant("GUARD_LO", ss.guard_lo or [], (m,)), _constant("GUARD_HI", ss.guard_hi or [], (m,)),
        _constant("GUARD_RATE", [LREAL_MAX if r is None else r for r in ss.guard_rate or []], (m,)),
        f"    GUARD_PERIOD : LREAL := {literal(ss.guard_period)};",
        f"    GUARD_INPUTS : BOOL := {'TRUE' if ss.guard and ss.guard_inputs else 'FALSE'};",
        _constant("GUARD_GAIN", ss.guard_gain or [], (m, n)),
        _constant("GUARD_IN_LO", ss.guard_in_lo or [], (n,)),
        _constant("GUARD_IN_HI", ss.guard_in_hi or [], (n,)),
        f"    USE_ADAPT : BOOL := {'TRUE' if ss.adapt != 'none' else 'FALSE'};",
        f"    ADAPT_RLS : BOOL := {'TRUE' if ss.adapt == 'rls' else 'FALSE'};",
        f"    MAX_GAIN_CHANGE : LREAL := {literal(ss.adapt_max_gain_change)};",
        f"    FORGETTING : LREAL := {literal(ss.adapt_forgetting)};",
        f"    MAX_BIAS : LREAL := {literal(ss.adapt_max_bias)};",
        f"    CAP_VARIANCE : LREAL := {literal(ss.adapt_var_cap)};",
        *monitor_constants(watch, literal, _constant)])
    kept = "\n".join(f"    {name}_kept : " + (f"ARRAY[{_dims(*shape)}] OF {kind};" if shape else f"{kind};")
                     for name, kind, shape in _memory(ss))
    save, restore = _copied(ss, back=False, indent="            "), _copied(ss, back=True)
    learned = "\n".join([_constant("gain", ss.adapt_gain or [1.0] * m, (m,)),
                         _constant("bias", ss.adapt_bias or [], (m,)),
                         _constant("variance", ss.adapt_var or [], (m,)),
                         _constant("cov", ss.adapt_cov or [], (m, 2, 2))])
    return f"""{banner(ss, "(*", "  ", "*)")}
(* The block's VAR are the stream's memory: declare its instance VAR RETAIN (or PERSISTENT) so that
   a warm restart of the PLC resumes the campaign; a cold start or a download resets them
   (first = TRUE): the next sample starts a campaign, and a model of changes from a campaign's
   first sample misses the warm-up before it. *)
FUNCTION_BLOCK {NAME}
VAR_INPUT
    u : ARRAY[{_dims(n)}] OF LREAL;
    time_s : LREAL;
    has_time : BOOL;
    reset : BOOL;
    ambient_c : LREAL;
    ref_valid : ARRAY[{_dims(m)}] OF BOOL;
    ref_error : ARRAY[{_dims(m)}] OF LREAL;
END_VAR
VAR_OUTPUT
    c : ARRAY[{_dims(m)}] OF LREAL;
    n_clamped : INT;
    refused : BOOL;
    repeated : BOOL;
    n_repeated : DINT;
{MONITOR_OUTPUTS}END_VAR
VAR
    first : BOOL := TRUE;
    u_last : ARRAY[{_dims(n)}] OF LREAL;
    u_read : ARRAY[{_dims(n)}] OF LREAL;
    buf : ARRAY[{_dims(taps, n)}] OF LREAL;
    ref : ARRAY[{_dims(n)}] OF LREAL;
    v0 : ARRAY[{_dims(n)}] OF LREAL;
    x0 : ARRAY[{_dims(2, n)}] OF LREAL;
    by_prev : ARRAY[{_dims(nb)}] OF LREAL;
    by_held : ARRAY[{_dims(nb)}] OF LREAL;
    excessed : BOOL;
    by_outright : ARRAY[{_dims(m)}] OF BOOL;
    gsum : LREAL;
    last : ARRAY[{_dims(n)}] OF LREAL;
    seen : ARRAY[{_dims(n)}] OF BOOL;
    uu : ARRAY[{_dims(n)}] OF LREAL;
    ra : LREAL;
    t0 : LREAL;
    init_start : ARRAY[{_dims(qi)}] OF LREAL;
    init_started : ARRAY[{_dims(qi)}] OF BOOL;
    any_seen : BOOL;
    rb : LREAL;
    hist : ARRAY[{_dims(2, d, n)}] OF LREAL;
    z : ARRAY[{_dims(2, k)}] OF LREAL;
    y_prev : ARRAY[{_dims(2, r)}] OF LREAL;
    ysum : ARRAY[{_dims(2, m)}] OF LREAL;
    excess : ARRAY[{_dims(sets, m)}] OF LREAL;
    serving : INT;
    serving_k : INT;    (* (st103c) the held sensor whose set is served; -1: none *)
    factor : ARRAY[{_dims(r)}] OF LREAL;
    a0 : LREAL;
    a0_known : BOOL;
    init_a0 : LREAL;
    init_n : LREAL;
    pg : LREAL;
    t_prev : LREAL;
    t_grid : LREAL;
    between : BOOL;
{kept}
    lag_dt : LREAL;
    t_read : LREAL;
    read_valid : BOOL;
    shift : LREAL;
    shift_valid : BOOL;
    t_back : LREAL;
    back_valid : BOOL;
    now : LREAL;
    v : ARRAY[{_dims(n)}] OF LREAL;
    x : ARRAY[{_dims(2, n + p + q)}] OF LREAL;
    ych : ARRAY[{_dims(2)}] OF LREAL;
    bound : LREAL;
    bound_held : ARRAY[{_dims(sets, m)}] OF LREAL;
    pat_z : ARRAY[{_dims(n)}] OF LREAL;
    pat_r : ARRAY[{_dims(n)}] OF LREAL;
    pat_p : LREAL;
    pat_r2 : LREAL;
    allow : ARRAY[{_dims(m)}] OF LREAL;
    gd : ARRAY[{_dims(n)}] OF LREAL;
    beyond : BOOL;
    on_pat : BOOL;
    w : LREAL;
    xl : ARRAY[{_dims(2, k)}] OF LREAL;
    e : LREAL;
    y : LREAL;
    dt : LREAL;
    lim : LREAL;
    dy : LREAL;
    kg : LREAL;
    p : LREAL;
    b : LREAL;
    g : LREAL;
    yo : LREAL;
    pp0 : LREAL;
    pp1 : LREAL;
    q0 : LREAL;
    q1 : LREAL;
    den : LREAL;
    k0 : LREAL;
    k1 : LREAL;
    err : LREAL;
    tr : LREAL;
    out_prev : ARRAY[{_dims(m)}] OF LREAL;
{learned}
    sw_on : ARRAY[{_dims(len(ss.switch_input))}] OF BOOL;
    sw_changed : ARRAY[{_dims(len(ss.switch_input))}] OF BOOL;
    sw_t0 : ARRAY[{_dims(len(ss.switch_input))}] OF LREAL;
    sw_now : BOOL;
    f32 : ARRAY[{_dims(len(ss.switch_feature))}] OF LREAL;
    tf : LREAL;
    zf : LREAL;
    fsum : LREAL;
    node : DINT;
    lstm_h : ARRAY[{_dims(len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden)}] OF LREAL;
    lstm_c : ARRAY[{_dims(len(ss.lstm_target), ss.lstm_layers, ss.lstm_hidden)}] OF LREAL;
    lstm_in : ARRAY[{_dims(ss.lstm_width)}] OF LREAL;
    lstm_a : ARRAY[{_dims(4 * ss.lstm_hidden)}] OF LREAL;
    la : LREAL;
    lb : LREAL;
    lg : LREAL;
    lsum : LREAL;
    lfac : LREAL;
    lx : LREAL;
    lq : INT;
    nk : INT;
    nl : INT;
    nr : INT;
    tree : DINT;
    i : INT;
    j : INT;
    l : INT;
    h : INT;
    r : INT;
{monitor_declarations(n, watch, _dims)}END_VAR
VAR CONSTANT
{consts}
END_VAR

IF reset THEN
    first := TRUE;
    FOR i := 0 TO N_OUTPUTS - 1 DO
        c[i] := 0.0;
    END_FOR;
END_IF;
{ST_REPEAT_RULE}IF NOT repeated THEN
FOR j := 0 TO N_INPUTS - 1 DO   (* (stwires100) as read: the monitor may read two exchanged *)
    u_read[j] := u[j];
END_FOR;
{MONITOR_BLOCK}\
(* an input not measured refuses the sample, as tc_step: not finite (NaN, infinity: every IEEE *)
(* comparison false) or beyond its U_LIMIT (a temperature's 10000 degC: an overload mark) *)
(* nothing remembered changes, c keeps the last corrections (0 before a campaign's first sample) *)
refused := FALSE;
FOR j := 0 TO N_INPUTS - 1 DO
    IF HELD[j] = 0 AND NOT (u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j]) THEN
        refused := TRUE;
    END_IF;
END_FOR;
(* (st93) so does a monitored reading beyond the monitor's range: no sensor rebuilds it here *)
(* (st109) but one beyond since the first sample, rebuilt as the C (mon_late) *)
IF mon_gone AND mon_late < 0 THEN
    refused := TRUE;
END_IF;
(* so does a campaign's first sample without its ambient given (AMBIENT_GIVEN: no sensor) *)
(* (stranger66: not where it is optional, AMBIENT_OPTIONAL: a lag's initial state alone reads it) *)
IF AMBIENT_GIVEN AND NOT AMBIENT_OPTIONAL AND first THEN
    IF NOT (ambient_c >= -REAL_LIMIT AND ambient_c <= REAL_LIMIT) THEN
        refused := TRUE;
    END_IF;
END_IF;
IF NOT refused THEN
    FOR j := 0 TO N_INPUTS - 1 DO   (* (dup99) the inputs as read *)
        u_last[j] := u_read[j];
    END_FOR;
{_indent(ST_TIME_RULE)}    n_clamped := 0;
    (* a missing signal of derived inputs only (HELD) is held at the campaign's last value, *)
    (* 0 before any (its derived inputs 0), as the diagnosed model holds its context *)
    FOR j := 0 TO N_INPUTS - 1 DO
        IF first THEN
            seen[j] := FALSE;
        END_IF;
        IF u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j] THEN
            uu[j] := u[j] - mon_shift[j];   (* (st93) a jump re-referenced *)
            last[j] := uu[j];
        ELSIF seen[j] THEN
            uu[j] := last[j];
        ELSE
            uu[j] := 0.0;
        END_IF;
    END_FOR;
    (* (st103b) a sensor no other predicts held out by BLIND_OUT, or (st103c) by its JUMP *)
    (* (mon_jheld, to the C's BACK), (st107) or both: each read at its last reading in, the *)
    (* correction the fallback model's (MON_FALLBACK_SET; 0: the model's) of the first held *)
    (* in the monitor's order that has one, as the C's *)
    serving := 0;
    serving_k := -1;
    IF mon_late >= 0 THEN    (* (st109) the C's stand-in plus the others' prediction of it *)
        uu[MON_INPUT[mon_late]] := MON_FIRST_C[mon_late] + mon_lpred;
    END_IF;
    IF mon_held >= 0 AND mon_held_set >= 0 THEN
        uu[MON_INPUT[mon_held]] := mon_base[mon_held] + mon_hlast;
        serving_k := mon_held;
    END_IF;
    IF mon_jheld >= 0 THEN
        uu[MON_INPUT[mon_jheld]] := mon_base[mon_jheld] + mon_jlast;
        IF serving_k < 0 OR MON_FALLBACK_SET[serving_k] = 0 THEN
            serving_k := mon_jheld;
        ELSIF mon_jheld < serving_k AND MON_FALLBACK_SET[mon_jheld] <> 0 THEN
            serving_k := mon_jheld;
        END_IF;
    END_IF;
    IF mon_rb >= 0 THEN    (* (st112b) one the C holds out after its lone jump: its rebuild *)
        uu[MON_INPUT[mon_rb]] := mon_base[mon_rb] + mon_rbx;
        serving_k := mon_rb;
    END_IF;
    IF serving_k >= 0 THEN
        serving := MON_FALLBACK_SET[serving_k];
    END_IF;
    (* causal FIR denoiser: newest raw sample first *)
    FOR l := TAPS - 1 TO 0 BY -1 DO
        FOR j := 0 TO N_INPUTS - 1 DO
            IF first OR l = 0 THEN
                buf[l, j] := uu[j];
            ELSE
                buf[l, j] := buf[l - 1, j];
            END_IF;
        END_FOR;
    END_FOR;
    (* the training grid (cadence72, timerule.on_grid): the model's memory steps by the time *)
    (* since the last sample it stepped on; a sample of a faster stream (a step of at most half *)
    (* GRID_PERIOD) less than a period after it (the one nearest a period on is stepped) is *)
    (* answered by the model's step from that one's state, which is kept (between73) *)
    between := FALSE;
    lag_dt := dt;
    IF GRID_PERIOD > 0.0 AND NOT first THEN
        lag_dt := now - t_grid;
        IF dt > 0.0 AND dt <= GRID_PERIOD / 2.0 AND lag_dt + dt / 2.0 < GRID_PERIOD THEN
            between := TRUE;
{save}
        END_IF;
    END_IF;
    IF NOT between THEN
        t_grid := now;
    END_IF;
    FOR j := 0 TO N_INPUTS - 1 DO
        v[j] := 0.0;
        FOR l := 0 TO TAPS - 1 DO
            v[j] := v[j] + buf[l, j] * FIR[l, j];
        END_FOR;
        IF first THEN
            IF REFERENCED[j] <> 0.0 THEN
                ref[j] := v[j];
            ELSE
                ref[j] := 0.0;
            END_IF;
        END_IF;
        x[0, j] := v[j] - ref[j];
        (* envelope (static limit): channel 1 is the excess over the bound *)
        x[1, j] := 0.0;
        IF CLAMP AND x[0, j] < LO[j] THEN
            x[1, j] := x[0, j] - LO[j];
            n_clamped := n_clamped + 1;
        ELSIF CLAMP AND x[0, j] > HI[j] THEN
            x[1, j] := x[0, j] - HI[j];
            n_clamped := n_clamped + 1;
        END_IF;
    END_FOR;
    (* the campaign's laws: by its initial ambient, the mean of the ambient inputs (ATI) *)
    IF first THEN
        a0 := 0.0;
        FOR l := 0 TO N_AMBIENT - 1 DO
            a0 := a0 + v[AMBIENT_INPUT[l]];
        END_FOR;
        a0 := a0 / AMBIENT_COUNT;
        a0_known := TRUE;
        IF AMBIENT_GIVEN THEN   (* no sensor: the campaign's, given at its first sample *)
            a0 := ambient_c;
            IF NOT (ambient_c >= -REAL_LIMIT AND ambient_c <= REAL_LIMIT) THEN
                a0 := 0.0;      (* optional and not given: no law reads it *)
                a0_known := FALSE;
            END_IF;
        END_IF;
        t0 := now;
        FOR r := 0 TO N_LAWS - 1 DO
            factor[r] := 0.0;
            IF a0 > LAW_LO[r] AND a0 <= LAW_HI[r] THEN
                factor[r] := 1.0;
                (* times (A0 - centre)^LAW_AMBIENT[r]: 0, 1 or 2 *)
                FOR l := 1 TO LAW_AMBIENT[r] DO
                    factor[r] := factor[r] * (a0 - AMBIENT_CENTRE);
                END_FOR;
            END_IF;
        END_FOR;
    END_IF;
    (* the guard's bound widens by the response to the inputs beyond their training range, at a *)
    (* sample on the training pattern (a hotter machine; one sensor leaving the others: not) *)
    beyond := FALSE;
    FOR j := 0 TO N_INPUTS - 1 DO
        gd[j] := 0.0;
        IF GUARD_INPUTS AND x[0, j] > GUARD_IN_HI[j] THEN
            gd[j] := x[0, j] - GUARD_IN_HI[j];
            beyond := TRUE;
        ELSIF GUARD_INPUTS AND x[0, j] < GUARD_IN_LO[j] THEN
            gd[j] := GUARD_IN_LO[j] - x[0, j];
            beyond := TRUE;
        END_IF;
    END_FOR;
    (* on the training pattern: the residual off its basis within the training one's (once, *)
    (* for the clamp and the guard alike) *)
    on_pat := FALSE;
    IF PATTERN AND (n_clamped > 0 OR beyond) THEN
        FOR j := 0 TO N_INPUTS - 1 DO
            pat_z[j] := (x[0, j] - PATTERN_MEAN[j]) / PATTERN_SCALE[j];
            pat_r[j] := pat_z[j];
        END_FOR;
        FOR l := 0 TO PATTERN_RANK - 1 DO
            pat_p := 0.0;
            FOR j := 0 TO N_INPUTS - 1 DO
                pat_p := pat_p + PATTERN_BASIS[j, l] * pat_z[j];
            END_FOR;
            FOR j := 0 TO N_INPUTS - 1 DO
                pat_r[j] := pat_r[j] - pat_p * PATTERN_BASIS[j, l];
            END_FOR;
        END_FOR;
        pat_r2 := 0.0;
        FOR j := 0 TO N_INPUTS - 1 DO
            pat_r2 := pat_r2 + pat_r[j] * pat_r[j];
        END_FOR;
        on_pat := pat_r2 <= PATTERN_TOL * PATTERN_TOL;
    END_IF;
    (* along the training pattern the clamp passes the inputs *)
    IF on_pat AND n_clamped > 0 THEN
        n_clamped := 0;
        FOR j := 0 TO N_INPUTS - 1 DO
            x[1, j] := 0.0;
        END_FOR;
    END_IF;
    FOR i := 0 TO N_OUTPUTS - 1 DO
        allow[i] := 0.0;
        IF on_pat AND beyond THEN
            FOR j := 0 TO N_INPUTS - 1 DO
                allow[i] := allow[i] + GUARD_GAIN[i, j] * gd[j];
            END_FOR;
        END_IF;
    END_FOR;
    (* static powers of machine states (Hammerstein): sign(w) |w|^e, w = v / scale *)
    FOR l := 0 TO N_POWERS - 1 DO
        w := v[POWER_SRC[l]] / POWER_SCALE[l];
        IF w < 0.0 THEN
            x[0, N_INPUTS + l] := -EXPT(-w, POWER_EXP[l]);
        ELSE
            x[0, N_INPUTS + l] := EXPT(w, POWER_EXP[l]);
        END_IF;
        x[1, N_INPUTS + l] := 0.0;
    END_FOR;
    (* a diagnosed model's derived inputs: r_a r_b (b < 0: r_a), r_j = v_j - its first *)
    (* value where REF (the effect's frame), 0 before any, as the stream's model reads its context *)
    FOR j := 0 TO N_INPUTS - 1 DO
        IF NOT seen[j] AND u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j] THEN
            v0[j] := v[j];
            seen[j] := TRUE;
        END_IF;
    END_FOR;
    (* the model's inputs and their excess at its first sample (a state times their rises) *)
    IF first THEN
        FOR j := 0 TO N_INPUTS - 1 DO
            x0[0, j] := x[0, j];
            x0[1, j] := x[1, j];
        END_FOR;
    END_IF;
    FOR l := 0 TO N_DERIVED - 1 DO
        ra := 0.0;
        IF seen[DERIVED_A[l]] THEN
            ra := v[DERIVED_A[l]];
            IF DERIVED_REF_A[l] <> 0 THEN
                ra := ra - v0[DERIVED_A[l]];
            END_IF;
        END_IF;
        rb := 1.0;
        IF DERIVED_B[l] >= 0 THEN
            rb := 0.0;
            IF seen[DERIVED_B[l]] THEN
                rb := v[DERIVED_B[l]];
                IF DERIVED_REF_B[l] <> 0 THEN
                    rb := rb - v0[DERIVED_B[l]];
                END_IF;
            END_IF;
            (* a rise over the air's: r_b - r_c, in r_b's frame *)
            IF DERIVED_OVER[l] >= 0 THEN
                IF seen[DERIVED_OVER[l]] THEN
                    IF DERIVED_REF_B[l] <> 0 THEN
                        rb := rb - (v[DERIVED_OVER[l]] - v0[DERIVED_OVER[l]]);
                    ELSE
                        rb := rb - v[DERIVED_OVER[l]];
                    END_IF;
                END_IF;
            END_IF;
        END_IF;
        IF DERIVED_CLAMPED[l] <> 0 THEN
            (* a state times the model input's rise, the clamped one's in channel 1 *)
            x[0, N_INPUTS + N_POWERS + l] := ra * (x[0, DERIVED_B[l]] - x0[0, DERIVED_B[l]]);
            x[1, N_INPUTS + N_POWERS + l] := ra * (x[1, DERIVED_B[l]] - x0[1, DERIVED_B[l]]);
        ELSE
            x[0, N_INPUTS + N_POWERS + l] := ra * rb;
            x[1, N_INPUTS + N_POWERS + l] := 0.0;
        END_IF;
    END_FOR;
    (* the clamp's gain grows by a state's value times its gain: the value of the sample before *)
    (* the campaign's first excess, held (out at its first sample: the target clamped outright) *)
    IF first THEN
        excessed := FALSE;
        FOR i := 0 TO N_OUTPUTS - 1 DO
            by_outright[i] := FALSE;
        END_FOR;
        FOR l := 0 TO N_STATE_GAIN - 1 DO
            by_held[l] := 0.0;
        END_FOR;
    END_IF;
    IF N_STATE_GAIN > 0 AND n_clamped > 0 AND NOT excessed THEN
        excessed := TRUE;
        IF first THEN
            FOR i := 0 TO N_OUTPUTS - 1 DO
                by_outright[i] := STATE_FIRST[i] <> 0;
            END_FOR;
        ELSE
            FOR l := 0 TO N_STATE_GAIN - 1 DO
                by_held[l] := by_prev[l];
            END_FOR;
        END_IF;
    END_IF;
    FOR l := 0 TO N_STATE_GAIN - 1 DO
        by_prev[l] := 0.0;
        IF seen[STATE_INPUT[l]] THEN
            by_prev[l] := v[STATE_INPUT[l]];
            IF STATE_REF[l] <> 0 THEN
                by_prev[l] := by_prev[l] - v0[STATE_INPUT[l]];
            END_IF;
        END_IF;
    END_FOR;
    (* a diagnosed lag's initial-state transient: w . (c(0) - A0) (1 - EXP(-(t - t0) / tau)), *)
    (* c(0) its sensors at the campaign's first sample that has one of them (a missing one: 0) *)
    FOR l := 0 TO N_INITIAL - 1 DO
        IF first THEN
            init_started[l] := FALSE;
            init_start[l] := 0.0;
        END_IF;
        IF NOT init_started[l] THEN
            any_seen := FALSE;
            w := 0.0;
            init_a0 := a0;
            IF NOT a0_known THEN   (* A0 not given: the mean of its sensors' first values *)
                init_a0 := 0.0;
                init_n := 0.0;
                FOR j := 0 TO N_INPUTS - 1 DO
                    IF INITIAL_SENSOR[l, j] <> 0 AND u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j] THEN
                        init_a0 := init_a0 + v[j];
                        init_n := init_n + 1.0;
                    END_IF;
                END_FOR;
                IF init_n > 0.0 THEN
                    init_a0 := init_a0 / init_n;
                END_IF;
            END_IF;
            FOR j := 0 TO N_INPUTS - 1 DO
                IF INITIAL_SENSOR[l, j] <> 0 AND u[j] >= -U_LIMIT[j] AND u[j] <= U_LIMIT[j] THEN
                    w := w + INITIAL_W[l, j] * (v[j] - init_a0);
                    any_seen := TRUE;
                END_IF;
            END_FOR;
            IF any_seen THEN
                init_start[l] := w;
                init_started[l] := TRUE;
            END_IF;
        END_IF;
        j := N_INPUTS + N_POWERS + N_DERIVED + l;
        x[0, j] := init_start[l] * (1.0 - EXP(-(now - t0) / INITIAL_TAU[l]));
        x[1, j] := 0.0;
    END_FOR;
    (* first-order lags *)
    FOR h := 0 TO 1 DO
        FOR l := 0 TO N_LAGS - 1 DO
            IF LAG_OF[l] >= 0 THEN   (* a cascade: a lag of a lag (after it), on its new value *)
                xl[h, l] := z[h, LAG_OF[l]];
            ELSE
                xl[h, l] := x[h, LAG_INPUT[l]];
            END_IF;
            IF first AND LAG_REST[l] <> 0 THEN   (* a machine state at rest (Hammerstein) *)
                z[h, l] := 0.0;
            ELSIF first THEN
                z[h, l] := xl[h, l];
            ELSE
                e := EXP(-lag_dt / TAU[l]);
                z[h, l] := e * z[h, l] + (1.0 - e) * xl[h, l];
            END_IF;
        END_FOR;
    END_FOR;
    IF first THEN
        FOR h := 0 TO 1 DO
            FOR l := 0 TO DEPTH - 1 DO
                FOR j := 0 TO N_INPUTS - 1 DO
                    hist[h, l, j] := x[h, j];
                END_FOR;
            END_FOR;
            FOR r := 0 TO N_LAWS - 1 DO
                y_prev[h, r] := 0.0;
            END_FOR;
        END_FOR;
    END_IF;
    (* outputs: static part, input history, lags, AR feedback; *)
    (* the excess's response out, within the held one *)
    FOR i := 0 TO N_OUTPUTS - 1 DO
        ysum[0, i] := 0.0;
        ysum[1, i] := 0.0;
        FOR l := 0 TO N_SETS - 1 DO
            excess[l, i] := 0.0;
        END_FOR;
    END_FOR;
    (* each law (its own feedback), times its factor, summed into its target where its set is *)
    (* served (LAW_SET: a fallback model's laws step beside the model's from the campaign's start) *)
    FOR r := 0 TO N_LAWS - 1 DO
        i := LAW_TARGET[r];
        pg := 0.0;
        FOR j := 0 TO N_INPUTS - 1 DO
            gsum := CLAMP_GAIN[r, j];
            FOR l := 0 TO N_STATE_GAIN - 1 DO
                gsum := gsum + by_held[l] * STATE_GAIN[r, l, j];
            END_FOR;
            pg := pg + gsum * x[1, j];
        END_FOR;
        IF factor[r] <> 0.0 THEN
            excess[LAW_SET[r], i] := excess[LAW_SET[r], i] + factor[r] * pg;
        END_IF;
        FOR h := 0 TO 1 DO
            IF h = 0 THEN
                ych[h] := INTERCEPT[r];
            ELSE
                ych[h] := 0.0;
            END_IF;
            FOR j := 0 TO N_INPUTS + N_POWERS + N_DERIVED + N_INITIAL - 1 DO
                ych[h] := ych[h] + B0[r, j] * x[h, j];
            END_FOR;
            FOR l := 0 TO DEPTH - 1 DO
                FOR j := 0 TO N_INPUTS - 1 DO
                    ych[h] := ych[h] + BD[r, l, j] * hist[h, l, j];
                END_FOR;
            END_FOR;
            FOR l := 0 TO N_LAGS - 1 DO
                ych[h] := ych[h] + G[r, l] * (z[h, l] - xl[h, l]);
            END_FOR;
            ych[h] := ych[h] + AR[r] * y_prev[h, r];
            y_prev[h, r] := ych[h];
            IF factor[r] <> 0.0 AND LAW_SET[r] = serving THEN
                ysum[h, i] := ysum[h, i] + factor[r] * ych[h];
            END_IF;
        END_FOR;
    END_FOR;
    (* an arx_rf model's forests on its machine states' switching, each times its weight and its *)
    (* ARX's law's factor (an ATI interval's: 0 outside it, not walked) added to its target: per tau *)
    (* a state's ramp 1 / (1 + EXP(-k (t - t0) / tau)) from its last change t0 *)
    (* (k +1 on, -1 off; before its first change the state, 0 or 1), rounded to REAL as *)
    (* scikit-learn's trees compare it; each tree walked from its root (at most TREE_DEPTH steps) *)
    IF N_FORESTS > 0 THEN
        tf := now;
        IF SWITCH_RAW_TIME AND has_time THEN
            tf := time_s;
        END_IF;
        FOR l := 0 TO N_SWITCHES - 1 DO
            sw_now := FALSE;
            IF SWITCH_INPUT[l] >= 0 THEN
                sw_now := v[SWITCH_INPUT[l]] > 0.5;
            END_IF;
            IF first THEN
                sw_changed[l] := FALSE;
            ELSIF sw_now <> sw_on[l] THEN
                sw_t0[l] := tf;
                sw_changed[l] := TRUE;
            END_IF;
            sw_on[l] := sw_now;
        END_FOR;
        FOR l := 0 TO N_FEATURES - 1 DO
            j := FEATURE_SWITCH[l];
            IF sw_changed[j] THEN
                zf := (tf - sw_t0[j]) / FEATURE_TAU[l];
                IF NOT sw_on[j] THEN
                    zf := -zf;
                END_IF;
                f32[l] := 1.0 / (1.0 + EXP(-zf));
            ELSIF sw_on[j] THEN
                f32[l] := 1.0;
            ELSE
                f32[l] := 0.0;
            END_IF;
            f32[l] := REAL_TO_LREAL(LREAL_TO_REAL(f32[l]));
        END_FOR;
        FOR l := 0 TO N_FORESTS - 1 DO
            lfac := factor[FOREST_LAW[l]];
            IF lfac <> 0.0 THEN
                fsum := 0.0;
                FOR tree := FOREST_TREES[l] TO FOREST_TREES[l + 1] - 1 DO
                    node := TREE_ROOT[tree];
                    FOR h := 1 TO TREE_DEPTH DO
                        IF NODE_LEFT[node] >= 0 THEN
                            IF f32[NODE_FEATURE[node]] <= NODE_THRESHOLD[node] THEN
                                node := NODE_LEFT[node];
                            ELSE
                                node := NODE_RIGHT[node];
                            END_IF;
                        END_IF;
                    END_FOR;
                    fsum := fsum + NODE_VALUE[node];
                END_FOR;
                i := FOREST_TARGET[l];
                fsum := fsum / DINT_TO_LREAL(FOREST_TREES[l + 1] - FOREST_TREES[l]);
                ysum[0, i] := ysum[0, i] + FOREST_WEIGHT[l] * lfac * fsum;
            END_IF;
        END_FOR;
    END_IF;
{LSTM_BLOCK}    t_prev := now;
    FOR i := 0 TO N_OUTPUTS - 1 DO
        ych[0] := ysum[0, i];
        ych[1] := ysum[1, i];
        (* back in range, the bound of the excess's last sample holds (each set's) *)
        IF first OR n_clamped > 0 THEN
            FOR l := 0 TO N_SETS - 1 DO
                bound := excess[l, i];
                IF bound < 0.0 THEN
                    bound := -bound;
                END_IF;
                bound_held[l, i] := bound;
            END_FOR;
        END_IF;
        bound := bound_held[serving, i];
        IF CLAMP_OUTRIGHT[i] <> 0 OR by_outright[i] THEN
            (* a model without a step gain: the response to the excess taken out whole *)
            bound := REAL_LIMIT;
        END_IF;
        IF CLAMP_SPREAD[i] <> 0 AND n_clamped >= 2 THEN
            (* a white target at a sample whose excess two inputs or more share: a heat source's *)
            bound := 0.0;
        END_IF;
        IF ych[1] > bound THEN
            y := ych[0] - bound;
        ELSIF ych[1] < -bound THEN
            y := ych[0] + bound;
        ELSE
            y := ych[0] - ych[1];
        END_IF;
        (* correction guard: within the rate limit of the previous output, then the bound *)
        IF USE_GUARD THEN
            IF NOT first THEN
                IF dt > GUARD_PERIOD THEN   (* a step or one training period, the longer *)
                    lim := GUARD_RATE[i] * dt;
                ELSE
                    lim := GUARD_RATE[i] * GUARD_PERIOD;
                END_IF;
                dy := y - out_prev[i];
                IF dy > lim THEN
                    y := out_prev[i] + lim;
                ELSIF dy < -lim THEN
                    y := out_prev[i] - lim;
                END_IF;
            END_IF;
            IF y < GUARD_LO[i] - allow[i] THEN
                y := GUARD_LO[i] - allow[i];
            ELSIF y > GUARD_HI[i] + allow[i] THEN
                y := GUARD_HI[i] + allow[i];
            END_IF;
        END_IF;
        out_prev[i] := y;
        IF USE_ADAPT THEN
            c[i] := -(gain[i] * y + bias[i]);
        ELSE
            c[i] := -y;
        END_IF;
    END_FOR;
    (* a reference measurement at this sample: the next corrections learn from it *)
    IF USE_ADAPT THEN
        FOR i := 0 TO N_OUTPUTS - 1 DO
            IF ref_valid[i] THEN
                IF ADAPT_RLS THEN
                    (* (gain, bias) by recursive least squares on phi = (y, 1) *)
                    yo := out_prev[i];
                    pp0 := cov[i, 0, 0] * yo + cov[i, 0, 1];
                    pp1 := cov[i, 1, 0] * yo + cov[i, 1, 1];
                    q0 := yo * cov[i, 0, 0] + cov[i, 1, 0];
                    q1 := yo * cov[i, 0, 1] + cov[i, 1, 1];
                    den := FORGETTING + (q0 * yo + q1);
                    k0 := pp0 / den;
                    k1 := pp1 / den;
                    err := ref_error[i] - (yo * gain[i] + bias[i]);
                    g := gain[i] + k0 * err;
                    b := bias[i] + k1 * err;
                    cov[i, 0, 0] := (cov[i, 0, 0] - k0 * q0) / FORGETTING;
                    cov[i, 0, 1] := (cov[i, 0, 1] - k0 * q1) / FORGETTING;
                    cov[i, 1, 0] := (cov[i, 1, 0] - k1 * q0) / FORGETTING;
                    cov[i, 1, 1] := (cov[i, 1, 1] - k1 * q1) / FORGETTING;
                    tr := cov[i, 0, 0] + cov[i, 1, 1];
                    IF CAP_VARIANCE > 0.0 AND tr / CAP_VARIANCE > 1.0 THEN
                        tr := tr / CAP_VARIANCE;
                        cov[i, 0, 0] := cov[i, 0, 0] / tr;
                        cov[i, 0, 1] := cov[i, 0, 1] / tr;
                        cov[i, 1, 0] := cov[i, 1, 0] / tr;
                        cov[i, 1, 1] := cov[i, 1, 1] / tr;
                    END_IF;
                    IF g < 1.0 - MAX_GAIN_CHANGE THEN
                        g := 1.0 - MAX_GAIN_CHANGE;
                    ELSIF g > 1.0 + MAX_GAIN_CHANGE THEN
                        g := 1.0 + MAX_GAIN_CHANGE;
                    END_IF;
                    gain[i] := g;
                ELSE
                    (* the bias alone: a scalar filter *)
                    p := variance[i];
                    kg := p / (FORGETTING + p);
                    b := bias[i] + kg * (ref_error[i] - gain[i] * out_prev[i] - bias[i]);
                    p := (p - kg * p) / FORGETTING;
                    IF CAP_VARIANCE > 0.0 AND p / CAP_VARIANCE > 1.0 THEN
                        p := p / (p / CAP_VARIANCE);
                    END_IF;
                    variance[i] := p;
                END_IF;
                IF b < -MAX_BIAS THEN
                    b := -MAX_BIAS;
                ELSIF b > MAX_BIAS THEN
                    b := MAX_BIAS;
                END_IF;
                bias[i] := b;
            END_IF;
        END_FOR;
    END_IF;
    FOR h := 0 TO 1 DO
        FOR l := DEPTH - 1 TO 0 BY -1 DO
            FOR j := 0 TO N_INPUTS - 1 DO
                IF l = 0 THEN
                    hist[h, l, j] := x[h, j];
                ELSE
                    hist[h, l, j] := hist[h, l - 1, j];
                END_IF;
            END_FOR;
        END_FOR;
    END_FOR;
    IF between THEN   (* the model's memory back to the grid sample's (between73) *)
{restore}
    END_IF;
    first := FALSE;
END_IF;
END_IF;   (* NOT repeated *)
END_FUNCTION_BLOCK
"""
