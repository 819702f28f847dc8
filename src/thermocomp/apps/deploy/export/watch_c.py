"""The code's sensor monitor (:mod:`.watch`) in C: its constants, its part of ``tc_state`` and
``monitor_step``, which ``tc_step`` calls on each sample after the time rule (cmon76)."""

from __future__ import annotations

import math

from ..surveillance.states import THAW, TREND_ROWS
from .watch import (
    BAND,
    EXCLUDED,
    FLAG_KINDS,
    NOT_IN_CODE,
    NOVEL,
    OUT,
    READMITTED,
    REASONS,
    REREFERENCED,
    RULES,
)


def header_part(ss) -> str:
    """The defines, the reasons and the monitored inputs (``compensator.h``, before the state)."""
    m = ss.monitor
    n = len(m.get("inputs", []))
    reasons = ", ".join(f'"{r}"' for r in REASONS)        # (plain ASCII, no quote in them)
    rules = "\n".join(f"#define TC_MON_{name} {k}" for k, name in enumerate(RULES) if k)
    kinds = ", ".join(f'"mon_{kind}"' for kind, _ in FLAG_KINDS)
    bits = ", ".join(str(bit) for _, bit in FLAG_KINDS)
    return f"""#define TC_MONITOR {int(bool(m))}   /* the sensor monitor in the code (docs/monitoring.md) */
#define TC_N_MONITORED {n}
#define TC_MON_WINDOW {max(int(m.get("window", 1)), 1)}
#define TC_MON_MODES {max(int(m.get("modes", 1)), 1)}   /* the POD basis's modes (cmon85: MON_PHI) */
#define TC_MON_THAW {THAW}   /* readings in a row off its held value that end a freeze (freeze84) */
/* (mon105d) the rows kept for the rate of a sensor that freezes (1: an export without spread) */
#define TC_MON_TREND {TREND_ROWS if any(v > 0 for v in m.get("spread", [])) else 1}
/* (dep106) ... one a step of MON_TAU / TC_MON_HALF s (frozen_hold.keeps: half spans tau) */
#define TC_MON_HALF {TREND_ROWS // 2}
/* tc_state.mon_flags, per sample: a sensor excluded, re-admitted, one out (the model reads its
   reconstruction), a judged sensor beyond its warning band, a rule of the served monitor that
   is not in the code fired (from here the code may part from the served model), sensors
   re-referenced by a common step (cmon80), and a new thermal state declared (cmon82b: no drift
   exclusion while it lasts, the guard's bound GUARD_LO_NEW / GUARD_HI_NEW) */
#define TC_MON_EXCLUDED {EXCLUDED}
#define TC_MON_READMITTED {READMITTED}
#define TC_MON_OUT {OUT}
#define TC_MON_BAND {BAND}
#define TC_MON_NOT_IN_CODE {NOT_IN_CODE}
#define TC_MON_REREFERENCED {REREFERENCED}
#define TC_MON_NEW_STATE {NOVEL}
/* tc_state.mon_rule indexes these (0: none); tc_state.mon_sensor the monitored sensor k, the
   input TC_MONITORED[k] */
{rules}
static const char *const TC_MONITOR_REASONS[{len(REASONS)}] = {{{reasons}}};
/* (cflags100) stream --flags: one 0/1 column per kind of mon_flags, named so (docs/cli.md) */
#define TC_N_FLAG_KINDS {len(FLAG_KINDS)}
static const char *const TC_FLAG_NAMES[{len(FLAG_KINDS)}] = {{{kinds}}};
static const int TC_FLAG_BITS[{len(FLAG_KINDS)}] = {{{bits}}};
static const int TC_MONITORED[{max(n, 1)}] = {{{", ".join(str(i) for i in m.get("inputs", [])) or "0"}}};
"""


STATE = """    /* the sensor monitor (TC_MONITOR): referenced readings d = u - mon_ref of the monitored
       inputs, their self-prediction errors over the last TC_MON_WINDOW samples (a ring) */
    double mon_ref[NM], mon_base[NM], mon_prev[NM], mon_prev_e[NM], mon_prev_other[NM];
    double mon_ref0[NM];   /* (cmon87) the reference before a sensor's first jump since it was in */
    int mon_late[NM];      /* (dep108) beyond its range since the campaign's first sample */
    double mon_last_step[NM];   /* (step93) each sensor's last one-sample change */
    /* (jump94b) each sensor's last 2 TC_MON_WINDOW - 1 readings on its current reference
       (oldest first) and the samples since that reference moved */
    double mon_settle[2 * TC_MON_WINDOW - 1][NM];
    int mon_settle_age[NM];
    double mon_hist[TC_MON_WINDOW][NM], mon_err[TC_MON_WINDOW][NM], mon_run_pred[NM];
    int mon_run[NM], mon_calm[NM], mon_pos, mon_count;
    /* (cdrop77) samples the next step spans (1 + its missing ones, or a gap in time), jumps
       re-referenced since it was last in, out for a dropout (its re-admission band) */
    double mon_gap[NM];
    int mon_jumps[NM], mon_dropped[NM];
    int mon_ranged[NM];   /* (cmon89b) out for a reading beyond its range (its leak judges it) */
    int mon_froze[NM], mon_off[NM];   /* (freeze84) out for a freeze alone, its readings in a
                                         row off the one it held (mon_held) */
    double mon_held[NM];
    /* (dep99) the sensors out, in the order they went out (mon_nout of them, any number: a
       logger card beyond range takes several at once, as served; cmon82: the second a blind
       partner, cmon85 a second out by drift) */
    int mon_out_set[NM], mon_nout;
    /* (cmon82) out by a drift exclusion, its exclusions so, the calm samples it needs to return,
       the sample count at its drift exclusion (-1: none) */
    int mon_by_field[NM], mon_outs[NM], mon_dwell[NM], mon_since[NM];
    /* (cmon85) the active set's operator and leverages (MON_M's, or solved: mon_operator); the
       second out may be any sensor out by a drift exclusion or a freeze */
    double mon_M[NM][NM], mon_lev[NM];
    double mon_slow[NM];     /* the field's memory (the served excursion rule, MON_TAU s) */
    int mon_slow_known;      /* 0: its age unknown (a sample without its time) */
    /* (cmon82b) a new thermal state declared, the samples since a judged sensor was last out of
       its warning band (it ends after a window of them) */
    int mon_novel, mon_calm_field;
    /* (cmon82c) out for explaining the others' errors (no other predicts it), and each sensor's
       last reading while it was in (what the model reads of one no other predicts, out) */
    int mon_hid[NM];   /* (mon85b) out as a culprit within its warning band: its whole band back */
    double mon_warn[NM], mon_alarm[NM];   /* (mon86) the bands of the set judged (mon_bands) */
    int mon_explains[NM], mon_fell;   /* (mon_fell: one whose fallback model the code lacks went out) */
    double mon_last[NM];
    /* (dep105b) the field the model read at the last sample (referenced; 0 before the first, as
       served's _clean): what it reads where nothing is left to rebuild a sensor from */
    double mon_clean[NM];
    int mon_read[NM];   /* (cmon84) the sample's monitored readings there (not missing) */
    int mon_flags, mon_sensor, mon_rule;        /* the last sample's (TC_MON_*) */
    int mon_perm[NM];   /* (wires100) monitored k reads sensor mon_perm[k]'s wire (exchanged) */
    /* (cmon92b) the sample's first rule not in the code and its sensor, where its first event
       (mon_rule) is another (an exclusion in the same sample): stream.c names both */
    int mon_missed, mon_missed_sensor;
    /* (mon105d) the last TC_MON_TREND referenced rows kept and their times (a ring at
       mon_past_pos), the sample's time, and per sensor out for a freeze until when its held
       value is read instead of its stand-in (-INFINITY: never); (dep106) one row a step of time,
       with its sample's number (mon_past_n), mon_rows the samples seen */
    double mon_past[TC_MON_TREND][NM], mon_past_t[TC_MON_TREND], mon_now, mon_hold_to[NM];
    double mon_past_n[TC_MON_TREND], mon_rows;
    int mon_past_pos;
"""


def state_part(ss) -> str:
    return STATE.replace("NM", str(max(len(ss.monitor.get("inputs", [])), 1)))


def monitor_arrays(ss) -> list[tuple[str, object, tuple, str]]:
    """The monitor's constants as :func:`.c._declared` takes them (zeros where there is none)."""
    m = ss.monitor
    n = len(m.get("inputs", []))
    pairs = m.get("pairs", [])
    vectors = ("warning", "alarm", "jump_lim", "lo_lim", "hi_lim", "lo_c", "hi_c", "seen_run",
               "blind_run", "rounding", "floor", "q_full", "bend_lim", "settle_lim",
               "spread",   # (mon105d: an export before it 0, a frozen sensor's stand-in)
               "first_c")   # (dep108: the served stand-in of a reading beyond range at the first)
    scalars = (("MON_MAX_LEV", "max_leverage", 1.0, "real"), ("MON_MIN_ACTIVE", "min_active", 0, "int"),
               ("MON_CONFIRM", "confirm", 1, "int"), ("MON_EXCLUDE_LEVEL", "exclude_level", 1, "int"),
               ("MON_PERIOD", "period", 1.0, "real"), ("MON_GAP_PERIODS", "gap_periods", 1.5, "real"),
               ("MON_READMIT", "readmit", 0.5, "real"), ("MON_COMMON_MIN", "common_min", 3, "int"),
               ("MON_COMMON_SPREAD", "common_spread", 2.0, "real"), ("MON_DRIFT", "drift", 0, "int"),
               ("MON_NEW_STATE", "new_state", 1, "int"),
               ("MON_NEW_STATE_OTHERS", "new_state_others", 2, "int"),
               ("MON_MAX_BACKOFF", "max_backoff", 10, "int"), ("MON_TAU", "tau", 1800.0, "real"),
               ("MON_GROWTH", "growth", 1.5, "real"), ("MON_NOVEL", "novel", 0, "int"),
               ("MON_BLIND_OUT", "blind_out", 0, "int"), ("MON_THAWED", "thawed", 0, "int"),
               ("MON_BLIND_DROP", "blind_drop", 0, "int"), ("MON_STEPPED", "stepped", 0, "int"),
               ("MON_CLEARED", "cleared", 0, "int"),
               ("MON_BLIND_JUMP", "blind_jump", 0, "int"),
               ("MON_SECOND_JUMP", "second_jump", 0, "int"),
               ("MON_SECOND_INSTANT", "second_instant", 0, "int"),
               ("MON_BLIND_RANGE", "blind_range", 0, "int"),
               ("MON_SECOND_RANGE", "second_range", 0, "int"),
               ("MON_SPIKE", "spike", 0, "int"), ("MON_BENT", "bent", 0, "int"),
               ("MON_PAIR_JUMP", "pair_jump", 0, "int"), ("MON_SETTLED", "settled", 0, "int"),
               ("MON_EXCHANGE", "exchange", 0, "int"),
               ("MON_SETTLE_STEADY", "settle_steady", 0.0, "real"), ("MON_LATE", "late", 0, "int"))
    modes = max(int(m.get("modes", 1)), 1)
    return [("MON_M", m.get("M", []), (n + 1 + len(pairs), n, n), "real"),
            ("MON_LEV", m.get("lev", []), (n + 1 + len(pairs), n), "real"),
            ("MON_PAIR_A", [p[0] for p in pairs], (len(pairs),), "int"),
            ("MON_PAIR_B", [p[1] for p in pairs], (len(pairs),), "int"),
            ("MON_N_PAIRS", len(pairs), (), "int"),
            ("MON_PHI", m.get("basis", []), (n, modes), "real"),
            ("MON_SOLVE", int(bool(m.get("solve")) and "basis" in m), (), "int"),
            ("MON_MOMENT", m.get("moment", [[0.0] * n for _ in range(n)]), (n, n), "real"),
            *((f"MON_{k.upper()}", m.get(k, [0.0] * n), (n,), "real") for k in vectors),
            # (mon97) a dithered reading frozen by its run alone (an export before it: never)
            ("MON_DITHER_RUN", m.get("dither_run", [math.inf] * n), (n,), "real"),
            ("MON_PREDICTABLE", m.get("predictable", []), (n,), "int"),
            ("MON_PORTED", m.get("ported_out", []), (n,), "int"),
            # (quiet94c) drift warned only (an ambient of a one-campaign training; before: none)
            ("MON_WARN_ONLY", m.get("warn_only", [0] * n), (n,), "int"),
            ("MON_FALLBACK", m.get("fallback", [0] * n), (n,), "int"),
            ("MON_FALLBACK_SET", m.get("fallback_set", [0] * n), (n,), "int"),
            *((name, m.get(key, default), (), kind) for name, key, default, kind in scalars)]


FUNCTIONS = r"""
#define NM (TC_N_MONITORED > 0 ? TC_N_MONITORED : 1)   /* (no monitor: never called) */
#define MW TC_MON_WINDOW
/* (dep99) 1: sensor k is in the out set */
static int mon_out_of(const tc_state *s, int k) {
    int p;
    for (p = 0; p < s->mon_nout; p++)
        if (s->mon_out_set[p] == k) return 1;
    return 0;
}

/* (dep99) the sensor in place p of the out set (0 the first out; -1: fewer out) */
static int mon_place(const tc_state *s, int p) {
    return p < s->mon_nout ? s->mon_out_set[p] : -1;
}

/* the active set (every sensor not in the out set): which sensors are in, judged (the others
   predict them) and each error's scale 1 / (1 - h) (an active one no other predicts: NAN, not
   judged) */
static void mon_set(const tc_state *s, int active[], int observable[], int judged[], double scale[]) {
    int k;
    for (k = 0; k < NM; k++) {
        double lev = s->mon_lev[k];
        active[k] = !mon_out_of(s, k);
        observable[k] = lev < MON_MAX_LEV;
        judged[k] = active[k] && observable[k];
        scale[k] = judged[k] ? 1.0 / (1.0 - lev > 1e-12 ? 1.0 - lev : 1e-12) : (active[k] ? NAN : 1.0);
    }
}

/* each sensor's prediction from the active ones (the POD operator of the set) and its error */
/* (quiet94c) of the judged sensors jd[], those whose error is the drift rule's evidence, as
   served (_judging): one MON_WARN_ONLY is warned (its band), never blamed, vetoing or holding */
static void mon_judging(int jd[]) {
    int k;
    for (k = 0; k < NM; k++) jd[k] = jd[k] && !MON_WARN_ONLY[k];
}

static void mon_errors(const tc_state *s, const double d[], double pred[], double e[]) {
    int a[NM], o[NM], jd[NM], k, m;
    double scale[NM];
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        pred[k] = 0.0;
        for (m = 0; m < NM; m++) pred[k] += s->mon_M[k][m] * (isfinite(d[m]) ? d[m] : 0.0);
        e[k] = (d[k] - pred[k]) * scale[k];
    }
}

/* (cmon82) the index of the operator with the sensors out[] out (-1: not in the code): every
   sensor in, one out, or a pair the code holds (a sensor and its blind partner) */
static int mon_op_of(const int out[]) {
    int k, a = -1, b = -1, n = 0, p;
    for (k = 0; k < NM; k++)
        if (out[k]) {
            if (n == 0) a = k; else b = k;
            n++;
        }
    if (n < 2) return a + 1;
    for (p = 0; n == 2 && p < MON_N_PAIRS; p++)
        if (MON_PAIR_A[p] == a && MON_PAIR_B[p] == b) return NM + 1 + p;
    return -1;
}

/* (cmon85) the operator M and leverages lev of the set with the sensors out[] out: one the code
   holds copied (MON_M), another solved from the POD basis (MON_SOLVE), as the served
   pod.operator: r = min(TC_MON_MODES, s) modes (s in), (qr103) Q R of Phi_a (s x r) by
   Gram-Schmidt twice (each column projected off the earlier ones two times, worked in W's rows:
   R^T R = G = Phi_a^T Phi_a, G never formed, so its condition is not squared), w_k = Q's row for
   k in, R^-T phi_k for k out, M[k][m] = w_k . w_m for m in, the leverage w_k . w_k (1 out).
   Fixed-size arrays, no allocation; at most 2 s r^2 + NM r^2 / 2 + NM^2 r multiply-adds.  0:
   neither (rank-deficient: R[p][p]^2, the part of column p the earlier ones do not span, within
   1e-12 of its squared norm G[p][p]: the Cholesky pivot test it replaces) */
static int mon_operator(const int out[], double M[][NM], double lev[]) {
    double R[TC_MON_MODES][TC_MON_MODES], g[TC_MON_MODES], W[NM][TC_MON_MODES], v;
    int k, m, p, q, c, r = 0, op = mon_op_of(out);
    if (op >= 0) {
        for (k = 0; k < NM; k++) {
            lev[k] = MON_LEV[op][k];
            for (m = 0; m < NM; m++) M[k][m] = MON_M[op][k][m];
        }
        return 1;
    }
    if (!MON_SOLVE) return 0;
    for (k = 0; k < NM; k++) r += !out[k];
    if (r > TC_MON_MODES) r = TC_MON_MODES;
    for (p = 0; p < r; p++) g[p] = 0.0;
    for (k = 0; k < NM; k++)
        for (p = 0; p < r && !out[k]; p++) {
            W[k][p] = MON_PHI[k][p];
            g[p] += W[k][p] * W[k][p];
        }
    for (q = 0; q < r; q++) {
        for (p = 0; p < q; p++) R[p][q] = 0.0;
        for (c = 0; c < 2; c++)         /* twice: Q's columns orthonormal to rounding */
            for (p = 0; p < q; p++) {
                for (v = 0.0, k = 0; k < NM; k++)
                    if (!out[k]) v += W[k][p] * W[k][q];
                R[p][q] += v;
                for (k = 0; k < NM; k++)
                    if (!out[k]) W[k][q] -= v * W[k][p];
            }
        for (v = 0.0, k = 0; k < NM; k++)
            if (!out[k]) v += W[k][q] * W[k][q];
        if (!(v > 1e-12 * (g[q] > 1e-300 ? g[q] : 1e-300))) return 0;
        R[q][q] = sqrt(v);
        for (k = 0; k < NM; k++)
            if (!out[k]) W[k][q] /= R[q][q];
    }
    for (k = 0; k < NM; k++)            /* the rows in keep Q's: R^-T phi_k would undo it */
        for (p = 0; p < r && out[k]; p++) {
            v = MON_PHI[k][p];
            for (c = 0; c < p; c++) v -= R[c][p] * W[k][c];
            W[k][p] = v / R[p][p];
        }
    for (k = 0; k < NM; k++) {
        for (m = 0; m < NM; m++) {
            M[k][m] = 0.0;
            for (p = 0; p < r && !out[m]; p++) M[k][m] += W[k][p] * W[m][p];
        }
        lev[k] = out[k] ? 1.0 : M[k][k];
    }
    return 1;
}

/* (mon86) the bands of the set in[] (the served _bands_of): each floor times
   sqrt(a' C a / MON_Q_FULL) (at least 1), a its row of (I - M) / (1 - h) in the set, C the training
   moment of the windowed snapshots, never below the whole set's bands; those where the set's
   operator is not had.  At most NM^3 + NM^2 multiply-adds, at a change of the set only */
static void mon_bands(const int in[], double warn[], double alarm[]) {
    double M[NM][NM], lev[NM], row[NM];
    int out[NM], k, m, c, all = 1, any = 0;
    for (k = 0; k < NM; k++) {
        warn[k] = MON_WARNING[k], alarm[k] = MON_ALARM[k];
        out[k] = !in[k], all = all && in[k], any = any || MON_FLOOR[k] > 0.0;
    }
    if (all || !any || !mon_operator(out, M, lev)) return;
    for (k = 0; k < NM; k++) {
        double q = 0.0, g;
        if (!in[k] || !(lev[k] < MON_MAX_LEV) || !(MON_Q_FULL[k] > 0.0)) continue;
        for (m = 0; m < NM; m++) row[m] = ((m == k) - (in[m] ? M[k][m] : 0.0)) / (1.0 - lev[k]);
        for (m = 0; m < NM; m++)
            for (c = 0; c < NM; c++) q += row[m] * MON_MOMENT[m][c] * row[c];
        if (!(q > MON_Q_FULL[k])) continue;
        g = sqrt(q / MON_Q_FULL[k]);
        if (MON_FLOOR[k] * g > warn[k]) warn[k] = MON_FLOOR[k] * g;
        if (2.0 * MON_FLOOR[k] * g > alarm[k]) alarm[k] = 2.0 * MON_FLOOR[k] * g;
    }
}

/* (mon86) the active set's bands, a culprit out within its band (mon_hid) counted in */
static void mon_set_bands(tc_state *s) {
    int in[NM], k;
    for (k = 0; k < NM; k++) in[k] = !mon_out_of(s, k) || s->mon_hid[k];
    if (s->mon_nout >= NM)      /* (dep105b) none in: the whole set's, as served */
        for (k = 0; k < NM; k++) in[k] = 1;
    mon_bands(in, s->mon_warn, s->mon_alarm);
}

/* the window's errors redone under a new operator (an exclusion, a re-admission) */
static void mon_recompute(tc_state *s) {
    double pred[NM];
    int w, out[NM];
    for (w = 0; w < NM; w++) out[w] = mon_out_of(s, w);
    mon_operator(out, s->mon_M, s->mon_lev);
    if (s->mon_nout >= NM) {    /* (dep105b) none in: no operator, as served's (M None): every
                                   prediction and error NAN, where the empty solve reads 0 */
        int k;
        for (w = 0; w < NM; w++)
            for (k = 0; k < NM; k++) s->mon_M[w][k] = NAN;
    }
    for (w = 0; w < MW; w++) {
        double e[NM];
        int k;
        mon_errors(s, s->mon_hist[w], pred, e);
        for (k = 0; k < NM; k++) s->mon_err[w][k] = e[k];
    }
    mon_set_bands(s);
}

/* the band (0 ok, 1 warning, 2 alarm) the last MON_CONFIRM errors of sensor k all exceed */
static int mon_level(const tc_state *s, int k) {
    double a = HUGE_VAL;
    int r;
    if (s->mon_count < MON_CONFIRM) return 0;
    for (r = 0; r < MON_CONFIRM; r++) {
        double v = fabs(s->mon_err[((s->mon_pos - 1 - r) % MW + MW) % MW][k]);
        if (isnan(v)) return 0;
        if (v < a) a = v;
    }
    return (a >= s->mon_warn[k]) + (a >= s->mon_alarm[k]);
}

/* (cmon82) the mean of the last MON_CONFIRM errors of sensor k */
static double mon_mean_err(const tc_state *s, int k) {
    double e = 0.0;
    int r, n = s->mon_count < MON_CONFIRM ? s->mon_count : MON_CONFIRM;
    for (r = 0; r < n; r++) e += s->mon_err[((s->mon_pos - 1 - r) % MW + MW) % MW][k];
    return n ? e / n : 0.0;
}

/* the sample's monitor fields cleared (flags, its first event and its first rule not in the
   code, cmon92b): by mon_refuses and monitor_step, whichever reads the sample first */
static void mon_clear(tc_state *s) {
    s->mon_flags = s->mon_rule = s->mon_missed = 0;
    s->mon_sensor = s->mon_missed_sensor = -1;
}

static void mon_flag(tc_state *s, int bit, int k, int rule) {
    s->mon_flags |= bit;
    if (!s->mon_rule) s->mon_sensor = k, s->mon_rule = rule;   /* the sample's first event */
    if (bit == TC_MON_NOT_IN_CODE && !s->mon_missed)   /* and its first rule not in the code */
        s->mon_missed_sensor = k, s->mon_missed = rule;
}

/* (cmon84) 1: sensor k, no other predicts it, held out at its last reading for a dropout or a
   freeze (as served: enough left in to rebuild the field without it) */
static int mon_drops(int k) {
    return MON_BLIND_DROP && !MON_PREDICTABLE[k] && NM - 1 >= MON_MIN_ACTIVE;
}

/* (cmon87) 1: sensor k, no other predicts it, held out for a jump as for a dropout (its jumps
   undone on its return where the reading returned: mon_undone) */
static int mon_spikes(int k) {
    return MON_BLIND_JUMP && mon_drops(k);
}

/* (cmon89b) 1: sensor k, no other predicts it, held out for a reading beyond its range, back
   only where its leak onto the others passes (mon_leak_passes), as served */
static int mon_ranges(int k) {
    return MON_BLIND_RANGE && mon_drops(k);
}

/* (mon98b) 1: sensor k, as mon_ranges, held out as the second too (served takes it out and may
   take back the first, out for explaining the others' errors, in the same sample) */
static int mon_second_range(int k) {
    return MON_SECOND_RANGE && mon_ranges(k);
}

/* (cmon87) sensor k, no other predicts it, back: its jumps undone as served (several are noise or
   a spike; of one, the reading nearer its held value taken), its reference restored and d[k]
   and its window shifted back */
static void mon_undone(tc_state *s, int k, double d[]) {
    double shift = s->mon_ref[k] - s->mon_ref0[k];
    int w;
    if (MON_PREDICTABLE[k] || !s->mon_jumps[k] || (s->mon_jumps[k] == 1
            && !(fabs(d[k] + shift - s->mon_last[k]) < fabs(d[k] - s->mon_last[k]))))
        return;
    s->mon_ref[k] = s->mon_ref0[k];
    d[k] += shift;
    for (w = 0; w < MW; w++) s->mon_hist[w][k] += shift;
}

/* (mon89) 1: sensor k, out for jumps alone and the others predicting it, jumping back within a
   window of its last jump to within its re-admission band of the field the active sensors
   predict (pred), on its reference before the first jump (x its reading): a spike, its
   reference put back (as served: _spike_back; d[k] the caller's) */
static int mon_spike_back(tc_state *s, int k, const double x[], const double d[],
                          const double pred[], const int a[]) {
    double M[NM][NM], L[NM], warn[NM], alarm[NM];
    int m, n = 0, out[NM], in[NM];
    if (!MON_SPIKE || a[k] || !MON_PREDICTABLE[k] || !s->mon_jumps[k] || s->mon_by_field[k]
        || s->mon_froze[k] || s->mon_dropped[k] || !(s->mon_calm[k] < MW))
        return 0;
    for (m = 0; m < NM; m++) {
        if (a[m] && !isfinite(d[m])) return 0;
        n += a[m];
        out[m] = !a[m] && m != k;
    }
    if (n < MON_MIN_ACTIVE || !mon_operator(out, M, L) || !(L[k] < MON_MAX_LEV)) return 0;
    for (m = 0; m < NM; m++) in[m] = !out[m] || s->mon_hid[m];
    mon_bands(in, warn, alarm);
    if (!(fabs(x[k] - s->mon_ref0[k] - pred[k]) < MON_READMIT * warn[k])) return 0;
    s->mon_ref[k] = s->mon_ref0[k];
    s->mon_jumps[k] = 0;
    return 1;
}

/* sensor k back in (rule: why), out of the out set (the others' order kept), the window
   re-judged (the numpy mirror's _readmit) */
static void mon_readmit(tc_state *s, int k, int rule) {
    int p, q = 0;
    s->mon_by_field[k] = s->mon_explains[k] = s->mon_ranged[k] = 0;
    for (p = 0; p < s->mon_nout; p++)
        if (s->mon_out_set[p] != k) s->mon_out_set[q++] = s->mon_out_set[p];
    s->mon_nout = q;
    mon_recompute(s);
    mon_flag(s, TC_MON_READMITTED, k, rule);
}

/* (cmon85) 1: sensor k out (a drift exclusion, a freeze) beside those out: a place free
   (the second; dep99: any, for a reading beyond range, as served; dep99b: and for a jump, which
   served re-references and takes out whatever the set; step99: and for a stepped error, served's
   stepped check having no cap either; dep100: and for a drift exclusion, its blind-out too, and a
   freeze, served's judgement and freeze check having none; dep105: and for a dropout beside two
   or more out where a sensor is left in, served's _instant having none) and the set's operator
   solved; (dep105b) a dropout that leaves none in too: served, no operator left, holds its last
   field, as the code now does (mon_recompute, mon_rebuilt; before, refused): whatever the rule
   now, so the rule is no argument */
static int mon_second_held(const tc_state *s, int k) {
    double M[NM][NM], lev[NM];
    int out[NM], m;
    if (!MON_SOLVE) return 0;
    for (m = 0; m < NM; m++) out[m] = m == k || mon_out_of(s, m);
    return mon_operator(out, M, lev);
}

/* 1: the code takes sensor k out beside those out for rule: one the others predict; (cmon89) for
   a dropout or a jump of one no other predicts (held at its last reading, as served) only where
   the field is rebuilt without them; (dep99) for a range reading wherever it is (read as missing
   while beyond, never fed back); (freezeu100) for a freeze of one no other predicts as for its
   dropout (served's freeze check has no cap and holds it at its last reading); (dep101) for a
   dropout wherever it is, of one no other predicts too (served's _instant takes every missing
   reading out; a returned one read where too few are in: mon_rebuilt, dep99) */
static int mon_second_kind(const tc_state *s, int k, int rule) {
    int m, in = 0;
    int blind = MON_SECOND_INSTANT && !MON_PORTED[k] && (
        rule == TC_MON_JUMP ? mon_spikes(k)
        : rule == TC_MON_FREEZE || rule == TC_MON_DROPOUT ? mon_drops(k)
        : rule == TC_MON_OFF_RANGE && mon_second_range(k));
    if (!(rule == TC_MON_DROPOUT || rule == TC_MON_OFF_RANGE || blind)) return MON_PORTED[k];
    for (m = 0; m < NM; m++) in += !mon_out_of(s, m);
    /* (dep105c) a jump wherever the field is: served holds a jumper at its last reading, no
       fallback while too few are in (the rebuild is a dropout's: its returned reading fed) */
    return (rule == TC_MON_OFF_RANGE || rule == TC_MON_DROPOUT || rule == TC_MON_JUMP
            || in - 1 >= MON_MIN_ACTIVE) && (MON_PORTED[k] || blind);
}

/* (cmon85, cmon86, cmon88; cmon89) 1: rule takes a second sensor out beside one */
static int mon_second_rule(int rule) {
    return rule == TC_MON_DRIFT_OUT || rule == TC_MON_FREEZE || rule == TC_MON_STEP_OUT
           || (rule == TC_MON_JUMP && MON_SECOND_JUMP)
           || ((rule == TC_MON_DROPOUT || rule == TC_MON_OFF_RANGE) && MON_SECOND_INSTANT);
}

/* 1: sensor k taken out for rule beside those out, as served: the rule takes a second, the
   others predict k (or cmon89's kinds) and the set is held or solved (cmon88: a jump) */
static int mon_second_taken(const tc_state *s, int k, int rule) {
    return mon_second_rule(rule) && mon_second_kind(s, k, rule) && mon_second_held(s, k);
}

/* (cmon93) 1: the code takes every sensor of ins[] out for rule (a jump; dep101: a dropout,
   several readings missing in one sample), in the monitor's order, as the first out (one it
   holds out: the others predict it, or cmon84 / cmon87 one no other predicts) or beside those
   out (cmon88 / cmon89's second, the set solved); the state as it was */
static int mon_pair_held(tc_state *s, const int ins[], int rule) {
    int n = s->mon_nout, k, ok = 1;
    for (k = 0; k < NM && ok; k++) {
        if (!ins[k]) continue;
        ok = s->mon_nout > 0 ? mon_second_taken(s, k, rule)
                             : MON_PORTED[k] || (rule == TC_MON_JUMP ? mon_spikes(k) : mon_drops(k));
        if (s->mon_nout < NM) s->mon_out_set[s->mon_nout++] = k;
    }
    s->mon_nout = n;   /* (the places past n are free: never read) */
    return ok;
}

/* (cmon89) 1: sensor k out the first, or any out where an instant fault may take one beside */
static int mon_is_out(const tc_state *s, int k) {
    return k >= 0 && (k == mon_place(s, 0) || (MON_SECOND_INSTANT && mon_out_of(s, k)));
}

/* k in the out set (its last place), its calm count and its within-band mark (mon85b)
   cleared: the served _exclude's, whatever took it out */
static void mon_put_out(tc_state *s, int k) {
    if (!mon_out_of(s, k) && s->mon_nout < NM) s->mon_out_set[s->mon_nout++] = k;
    s->mon_calm[k] = s->mon_hid[k] = 0;
}

/* sensor k out where the code holds it (one out, the others predicting it, or a dropout or a
   freeze of one no other predicts; cmon85: a second, for a drift, a freeze or cmon86 a stepped
   error, cmon88 a jump); else flagged */
static void mon_exclude(tc_state *s, int k, int rule) {
    int blind = ((rule == TC_MON_DROPOUT || rule == TC_MON_FREEZE) && mon_drops(k))
                || (rule == TC_MON_JUMP && mon_spikes(k))
                || (rule == TC_MON_OFF_RANGE && mon_ranges(k));
    int second = s->mon_nout > 0 && !mon_second_taken(s, k, rule);
    if (second || !(MON_PORTED[k] || blind)) {
        mon_flag(s, TC_MON_NOT_IN_CODE, k, second ? TC_MON_SECOND : TC_MON_BLIND);
        return;
    }
    mon_put_out(s, k);
    mon_recompute(s);
    mon_flag(s, TC_MON_EXCLUDED, k, rule);
    if (MON_FALLBACK[k] && !MON_FALLBACK_SET[k]) s->mon_fell = 1;   /* (none in the code) */
}

/* (mon88) 1: a sensor out of the set trial, frozen by the rule for one no other predicts (its
   reading constant longer than MON_BLIND_RUN), would predict sensor j (as served) */
static int mon_blind_for_frozen(const tc_state *s, int j, const int trial[]) {
    double M[NM][NM], L[NM];
    int k, m, out[NM];
    for (k = 0; k < NM; k++) {
        if (trial[k] || !mon_out_of(s, k) || !(s->mon_run[k] > MON_BLIND_RUN[k]))
            continue;
        for (m = 0; m < NM; m++) out[m] = !trial[m] && m != k;
        if (mon_operator(out, M, L) && L[j] < MON_MAX_LEV) return 1;
    }
    return 0;
}

/* (cmon89b) 1: the leak of sensor u onto the sensors judged in the set trial with it (M, L)
   and without it is within MON_READMIT of their warning bands on every sample of the window, as
   served (Readmission._leak_passes): also where too few are left without it to judge; 0 where
   the set without it has no operator in the code */
static int mon_leak_passes(const tc_state *s, int u, const int trial[], double M[][NM],
                           const double L[]) {
    double M2[NM][NM], L2[NM];
    int k, w, m, n = 0, out[NM], both[NM];
    for (k = 0; k < NM; k++) out[k] = !trial[k] || k == u, n += !out[k];
    if (n < MON_MIN_ACTIVE) return 1;
    if (!mon_operator(out, M2, L2)) return 0;
    for (k = 0; k < NM; k++) both[k] = !out[k] && L[k] < MON_MAX_LEV && L2[k] < MON_MAX_LEV;
    for (w = 0; w < MW; w++)
        for (k = 0; k < NM; k++) {
            double h, p = 0.0, p2 = 0.0, v;
            if (!both[k]) continue;
            h = isfinite(s->mon_hist[w][k]) ? s->mon_hist[w][k] : 0.0;
            for (m = 0; m < NM; m++) {
                double x = isfinite(s->mon_hist[w][m]) ? s->mon_hist[w][m] : 0.0;
                p += M[k][m] * x;
                p2 += M2[k][m] * x;
            }
            v = fabs((h - p) / (1.0 - L[k]) - (h - p2) / (1.0 - L2[k])) / MON_WARNING[k];
            if (!(v < MON_READMIT)) return 0;
        }
    return 1;
}

/* re-admission (cmon82: judged together, as served): ok[k] whether sensor k of the set trial
   passes, its leave-one-out error in it over the whole window within MON_READMIT of its warning
   band (one out for a dropout alone: its whole band; one the others in trial cannot predict:
   where no other predicts it at all), worst[k] that error */
static void mon_pass_once_back(const tc_state *s, const int trial[], int ok[], double worst[]) {
    double M[NM][NM], L[NM], warn[NM], alarm[NM];
    int k, w, m, n = 0, out[NM], in[NM];
    for (k = 0; k < NM; k++) n += trial[k], out[k] = !trial[k], ok[k] = 0, worst[k] = HUGE_VAL;
    if (n < MON_MIN_ACTIVE || !mon_operator(out, M, L)) return;
    for (k = 0; k < NM; k++) in[k] = trial[k] || s->mon_hid[k];
    mon_bands(in, warn, alarm);   /* (mon86) the trial set's */
    for (k = 0; k < NM; k++) {
        double lev = L[k], band;
        if (!trial[k]) continue;
        if (lev >= MON_MAX_LEV) {
            ok[k] = !MON_PREDICTABLE[k];
            continue;
        }
        band = ((s->mon_dropped[k] && !s->mon_by_field[k] && !s->mon_jumps[k]) || s->mon_hid[k])
            ? 1.0 : MON_READMIT;
        worst[k] = 0.0;
        for (w = 0; w < MW; w++) {
            double p = 0.0, v;
            for (m = 0; m < NM; m++)
                p += M[k][m] * (isfinite(s->mon_hist[w][m]) ? s->mon_hist[w][m] : 0.0);
            v = fabs(((isfinite(s->mon_hist[w][k]) ? s->mon_hist[w][k] : 0.0) - p) / (1.0 - lev));
            if (v > worst[k]) worst[k] = v;
        }
        ok[k] = worst[k] < band * warn[k];
    }
    /* (cmon82c) one out for explaining the others' errors: back where they all pass their
       warning band with it in, as served */
    for (k = 0; k < NM; k++)
        if (trial[k] && L[k] >= MON_MAX_LEV && s->mon_explains[k]) {
            ok[k] = 1;
            for (m = 0; m < NM; m++)
                if (trial[m] && L[m] < MON_MAX_LEV && !(worst[m] < warn[m])) ok[k] = 0;
        }
    /* (mon88) one out by the field's judgement, blind only for want of a partner out frozen */
    for (k = 0; k < NM && MON_CLEARED; k++)
        if (trial[k] && L[k] >= MON_MAX_LEV && s->mon_by_field[k] && !s->mon_explains[k]
            && mon_out_of(s, k))
            ok[k] = mon_blind_for_frozen(s, k, trial);
    /* (cmon89b) one no other predicts, out of range: back where its leak passes, as served */
    for (k = 0; k < NM; k++)
        if (ok[k] && mon_out_of(s, k) && mon_ranges(k) && s->mon_ranged[k])
            ok[k] = mon_leak_passes(s, k, trial, M, L);
}

/* which of the due sensors come back (back[]): those that pass in the set of the active ones
   and every due one, the worst failing one left out until the rest pass */
static void mon_returning(const tc_state *s, const int due[], int back[]) {
    int trial[NM], ok[NM], k;
    double worst[NM];
    for (k = 0; k < NM; k++) trial[k] = !mon_out_of(s, k) || due[k];
    for (;;) {
        int bad = -1;
        mon_pass_once_back(s, trial, ok, worst);
        for (k = 0; k < NM; k++)
            if (due[k] && trial[k] && !ok[k] && (bad < 0 || worst[k] > worst[bad])) bad = k;
        if (bad < 0) break;
        trial[bad] = 0;
    }
    for (k = 0; k < NM; k++) back[k] = due[k] && trial[k];
}

/* 1: input j is a monitored one (its missing reading the monitor's) */
static int mon_watched(int j) {
    int k;
    for (k = 0; k < TC_N_MONITORED; k++)
        if (TC_MONITORED[k] == j) return 1;
    return 0;
}

/* (cdrop77) the rule by which the sample u is refused for a missing monitored reading the code
   cannot rebuild (0: taken): at a campaign's first sample, with another sensor out or missing
   (or out of range), of a sensor the code does not hold out; flagged in mon_flags / mon_rule */
static int mon_refuses(tc_state *s, const double u[]) {
    int k, j = -1, nnew = 0, miss = -1, rng = 0, rule = 0, fresh[NM];
    mon_clear(s);
    for (k = 0; k < TC_N_MONITORED; k++) {
        int input = TC_MONITORED[s->first ? k : s->mon_perm[k]];   /* (wires100: as read) */
        double x = u[input];
        fresh[k] = 0;
        if (!measured(u, input)) {
            if (miss < 0) miss = k;
            if (s->first || !mon_is_out(s, k)) {
                if (j < 0) j = k;
                nnew++;
                fresh[k] = 1;
            }
        } else if (x < MON_LO_LIM[k] || x > MON_HI_LIM[k]) rng = 1;
    }
    if (miss < 0) return 0;
    if (s->first) rule = TC_MON_MISSING_FIRST;
    else if (nnew && (rng || ((nnew > 1 || s->mon_nout > 0)
                              && !mon_pair_held(s, fresh, TC_MON_DROPOUT))))
        rule = TC_MON_MISSING_SECOND;   /* (cmon89: a dropout as the second out taken; dep101:
                                           several new ones, each out in turn) */
    else if (nnew && !MON_PORTED[j] && !mon_drops(j)) rule = TC_MON_MISSING_BLIND;
    if (rule) mon_flag(s, TC_MON_NOT_IN_CODE, j >= 0 ? j : miss, rule);
    return rule;
}

/* the monitored inputs of u as the model reads them: the reading, a sensor out rebuilt (one no
   other predicts held at its last reading in); (dep99) where too few are in to rebuild the field,
   one out for a dropout alone whose reading is back and moved read, as served (_rebuilds) */
static void mon_rebuilt(tc_state *s, double u[], const double d[], const double pred[]) {
    int k, in = 0;
    for (k = 0; k < NM; k++) in += !mon_out_of(s, k);
    for (k = 0; k < NM; k++) {
        int read = !mon_out_of(s, k) || (in < MON_MIN_ACTIVE && s->mon_dropped[k]
                                         && isfinite(d[k]) && s->mon_run[k] == 0);
        /* (mon105d) out for a freeze alone: its held value while its past allows */
        int held = s->mon_froze[k] && s->mon_off[k] == 0 && s->mon_now <= s->mon_hold_to[k];
        double v = read ? d[k] : MON_PREDICTABLE[k] && !held ? pred[k] : s->mon_last[k];
        if (!isfinite(v)) v = s->mon_clean[k];   /* (dep105b) nothing to rebuild from: the last
                                                   field, as served */
        s->mon_clean[k] = v;
        u[TC_MONITORED[k]] = s->mon_base[k] + v;
    }
    if (s->mon_nout) s->mon_flags |= TC_MON_OUT;
    if (s->mon_novel) s->mon_flags |= TC_MON_NEW_STATE;
    for (k = 0; k < NM && s->mon_fell; k++)   /* the served correction is the fallback's */
        if (MON_FALLBACK[k]) {
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_FALLBACK);
            break;
        }
}

/* (cmon83) the law set the correction sums (LAW_SET): the fallback model's of the first sensor
   out that has one, as served (not while too few are in to rebuild the field, nor of one out for
   a dropout that reads again, cmon84: its held reading the model's while it waits out its
   window; one whose model is not in the code: 0, flagged FALLBACK); 0: the model's */
static int mon_serving(const tc_state *s) {
    int k, in = 0;
    for (k = 0; k < NM; k++) in += !mon_out_of(s, k);
    if (in < MON_MIN_ACTIVE) return 0;
    for (k = 0; k < NM; k++)
        if (mon_out_of(s, k) && MON_FALLBACK[k]
                && !(s->mon_dropped[k] && s->mon_read[k])) return MON_FALLBACK_SET[k];
    return 0;
}

/* (cmon80) the readings beyond their range (rng[]: which, nrng of them) after a campaign's
   first sample: 1 each still in rng[] read as missing, those read cleared from it (the others in
   and within range predict it beyond the same training edge by more than its warning band and
   it reads nearer that than half its distance from the edge: a machine hotter than training),
   -1 not in the code (flagged; rng[] as it was): every reading beyond (kelvin97), one of a sensor
   the code does not hold out, or beside those out where the set's operator is not had.  (dep99)
   Several at once are each out, in the monitor's order, the set of any size, as served */
static int mon_beyond(tc_state *s, const double x[], const double d[], int rng[], int nrng) {
    double M[NM][NM], lev[NM];
    int m, j, out[NM], kept[NM], saved[NM], nsaved = s->mon_nout, nin = 0, op, r = 1;
    for (j = 0; j < NM && !rng[j]; j++) ;
    if (j == NM) return 0;   /* (none beyond; said so that gcc -O2 -Warray-bounds, inlining
                                this into the step, does not index MON_PREDICTABLE[NM]) */
    if (nrng == NM) {
        mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_RANGE);
        return -1;
    }
    for (m = 0; m < NM; m++) {   /* predicted from the others in and within range */
        out[m] = mon_out_of(s, m) || rng[m] || !isfinite(d[m]);
        nin += !out[m];
        kept[m] = rng[m];
        saved[m] = s->mon_out_set[m];
    }
    op = nin >= MON_MIN_ACTIVE && mon_operator(out, M, lev);
    for (j = 0; j < NM && r > 0; j++) {   /* (the set grown as the caller takes them out) */
        if (!rng[j]) continue;
        if (s->mon_nout > 0 && !mon_is_out(s, j) && !(
                MON_SECOND_INSTANT && mon_second_kind(s, j, TC_MON_OFF_RANGE)
                && mon_second_held(s, j))) {
            mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_RANGE);
            r = -1;
        } else if (mon_is_out(s, j)) {   /* out already: read as missing */
            if (!MON_PREDICTABLE[j] && !(mon_ranges(j) && (j == mon_place(s, 0)
                                                          || mon_second_range(j)))) {
                /* (served: its leak judges its return) */
                mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_BLIND);
                r = -1;
            }
        } else {
            if (op) {
                double p = 0.0, edge;
                int up = x[j] > MON_HI_C[j], beyond;
                for (m = 0; m < NM; m++) p += M[j][m] * (out[m] ? 0.0 : d[m]);
                p += x[j] - d[j];
                edge = up ? MON_HI_C[j] : MON_LO_C[j];
                beyond = (up ? p - edge : edge - p) > MON_WARNING[j];
                if (beyond && fabs(x[j] - p) < 0.5 * fabs(x[j] - edge)) {
                    kept[j] = 0;   /* a machine hotter than training: read */
                    continue;
                }
            }
            if (!MON_PORTED[j] && !mon_ranges(j)) {
                mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_BLIND);
                r = -1;
            } else if (s->mon_nout < NM) s->mon_out_set[s->mon_nout++] = j;
        }
    }
    s->mon_nout = nsaved;
    for (m = 0; m < NM; m++) s->mon_out_set[m] = saved[m];
    if (r < 0) return -1;
    for (m = 0; m < NM; m++) rng[m] = kept[m];
    return 1;
}

/* (cmon80) a common step: at least MON_COMMON_MIN sensors jumping in one sample (big), the
   median of their steps the common one; every active sensor within a factor MON_COMMON_SPREAD
   of it re-referenced by its own step and kept in, where they are more than half the active
   ones read (called with at least MON_COMMON_MIN of them).  The jumps left after it: big
   changed */
static void mon_common_step(tc_state *s, double d[], double step[], int big[], int pos) {
    double v[NM], common, r;
    int took[NM], k, i, n = 0, ntook = 0, njump = 0, nread = 0;
    for (k = 0; k < NM; k++)
        if (big[k]) {   /* (their steps sorted) */
            for (i = n; i > 0 && v[i - 1] > step[k]; i--) v[i] = v[i - 1];
            v[i] = step[k];
            n++;
        }
    common = n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2.0;
    for (k = 0; k < NM; k++) {
        r = common != 0.0 ? step[k] / common : 0.0;
        took[k] = !mon_out_of(s, k) && r >= 1.0 / MON_COMMON_SPREAD
                  && r <= MON_COMMON_SPREAD;
        ntook += took[k];
        njump += took[k] && big[k];
        nread += !mon_out_of(s, k) && isfinite(d[k]);
    }
    if (njump < MON_COMMON_MIN || 2 * ntook <= nread) return;
    for (k = 0; k < NM; k++) {
        if (!took[k]) continue;
        s->mon_ref[k] += step[k];
        d[k] -= step[k];
        s->mon_hist[pos][k] = d[k];
    }
    for (k = 0; k < NM; k++) if (took[k]) break;
    mon_flag(s, TC_MON_REREFERENCED, k, TC_MON_COMMON_STEP);
    for (k = 0; k < NM; k++)
        if (took[k]) step[k] = 0.0, big[k] = 0;
}

/* (step93) a step of a sensor no other predicts off its own last one by more than MON_BEND_LIM
   (not a jump, read, no gap; none for a sensor out or back): re-referenced by the departure and
   kept in, counted a jump (mon_ref0); (step93b) a second since it was in is a jump (big) */
static void mon_bent(tc_state *s, double d[], double step[], int big[], const int gone[],
                     const double gap[], int pos) {
    double off;
    int k;
    for (k = 0; k < NM; k++) {
        off = step[k] - s->mon_last_step[k];
        if (big[k] || gone[k] || gap[k] != 1.0 || !(fabs(off) > MON_BEND_LIM[k])) continue;
        if (s->mon_jumps[k]) { big[k] = 1; continue; }
        s->mon_ref0[k] = s->mon_ref[k];
        s->mon_jumps[k] = 1;
        s->mon_ref[k] += off;
        d[k] -= off;
        step[k] -= off;
        s->mon_hist[pos][k] = d[k];
        mon_flag(s, TC_MON_REREFERENCED, k, TC_MON_BENT);
    }
}

/* (cmon93) the change since the last sample of each sensor of big[] as the active ones that did
   not jump predict it (one operator on that set, as served: _unjumped_change), in expected[]:
   NAN where they cannot (fewer than MON_MIN_ACTIVE of them, or its leverage with them at the
   limit).  0: the code has no operator of a set (expected[] not to be read) */
static int mon_change_seen(const tc_state *s, const double d[], int out[], const int which[],
                           double expected[]);   /* (below) */
static int mon_unjumped(const tc_state *s, const double d[], const int big[], double expected[]) {
    int out[NM], k, nbase = 0;
    for (k = 0; k < NM; k++) {
        out[k] = mon_out_of(s, k) || big[k] || !isfinite(s->mon_prev[k]);
        nbase += !out[k];
        expected[k] = NAN;
    }
    if (nbase < MON_MIN_ACTIVE) return 1;
    return mon_change_seen(s, d, out, big, expected);
}

/* the change since the last sample of each which[] sensor as the sensors not out[] predict it
   (one operator on that set), NAN where they cannot (its leverage with them at the limit): the
   jump's expected change (mon_unjumped) and (wires100) the exchanged wires' prediction alike.
   0: the code has no operator of a set */
static int mon_change_seen(const tc_state *s, const double d[], int out[], const int which[],
                           double expected[]) {
    double M[NM][NM], lev[NM], Mj[NM][NM], levj[NM];
    int k, m;
    for (k = 0; k < NM; k++) expected[k] = NAN;
    if (!mon_operator(out, M, lev)) return 0;
    for (k = 0; k < NM; k++) {
        if (!which[k]) continue;
        out[k] = 0;   /* (its leverage with the set) */
        if (!mon_operator(out, Mj, levj)) return 0;
        out[k] = 1;
        if (!(levj[k] < MON_MAX_LEV)) continue;
        expected[k] = 0.0;
        for (m = 0; m < NM; m++)
            if (!out[m]) expected[k] += M[k][m] * (d[m] - s->mon_prev[m]);
    }
    return 1;
}

/* (cmon93) two sensors jumping in one sample (big[]), no common step, every reading there and in
   range, as the served monitor reads a sample's instant faults together (_spike_back, _instant):
   where both are out, each tried as a spike's return first (mon89, in the monitor's order, the
   field's prediction redone after a return; dep109: none on a sample with a value not finite, a
   late reference's, as served); every jumper left re-referenced by its step less
   its change as the active sensors that did not jump predict it (mon_unjumped; alone, its whole
   step), those in excluded in the monitor's order.  1: held (instant[] the jumpers
   re-referenced, d[] changed); 0: not in the code (a third out, a set it cannot solve, one it
   does not hold out), nothing changed, flagged by the caller as before */
static int mon_pair_jump(tc_state *s, const double x[], double d[], const double step[],
                         const int big[], int instant[]) {
    double pred[NM], e[NM], expected[NM], scale[NM];
    int a[NM], o[NM], jd[NM], left[NM], ins[NM], k, nleft = 0, anyin = 0, unread = 0;
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++)
        left[k] = big[k], anyin = anyin || (big[k] && a[k]), unread = unread || !isfinite(d[k]);
    for (k = 0; k < NM && MON_SPIKE && !anyin && !unread; k++) {   /* both out: a spike's return first */
        if (!big[k]) continue;
        mon_errors(s, d, pred, e);
        mon_set(s, a, o, jd, scale);
        if (!mon_spike_back(s, k, x, d, pred, a)) continue;
        d[k] = x[k] - s->mon_ref[k];
        mon_readmit(s, k, TC_MON_SPIKE);
        left[k] = 0;
    }
    for (k = 0; k < NM; k++) nleft += left[k], expected[k] = NAN;
    if (nleft >= 2 && !mon_unjumped(s, d, left, expected)) return 0;
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) ins[k] = left[k] && a[k];
    if (!mon_pair_held(s, ins, TC_MON_JUMP)) return 0;
    for (k = 0; k < NM; k++) {
        double offset;
        if (!left[k]) continue;
        if (!a[k] && !MON_PREDICTABLE[k] && !MON_BLIND_JUMP)   /* (cmon82c) the served return
                                                                 may undo it */
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_BLIND);
        if (!s->mon_jumps[k]) s->mon_ref0[k] = s->mon_ref[k];
        offset = step[k] - (isfinite(expected[k]) ? expected[k] : 0.0);
        s->mon_ref[k] += offset;
        d[k] -= offset;
        s->mon_jumps[k]++;
        instant[k] = 1;
    }
    for (k = 0; k < NM; k++)
        if (ins[k]) mon_exclude(s, k, TC_MON_JUMP);
    return 1;
}

/* (cmon82) the exclusion by judgement: the last MON_CONFIRM rows of the window, NAN as 0 */
static int mon_rows(const tc_state *s, double X[][NM]) {
    int r, k, n = s->mon_count < MON_CONFIRM ? s->mon_count : MON_CONFIRM;
    for (r = 0; r < n; r++)
        for (k = 0; k < NM; k++) {
            double v = s->mon_hist[((s->mon_pos - 1 - r) % MW + MW) % MW][k];
            X[r][k] = isfinite(v) ? v : 0.0;
        }
    return n;
}

/* sensor k's leave-one-out error under the operator M (leverages lev) in row x */
static double mon_loo(double M[][NM], const double lev[], int k, const double x[]) {
    double p = 0.0;
    int m;
    for (m = 0; m < NM; m++) p += M[k][m] * x[m];
    return (x[k] - p) / (1.0 - lev[k]);
}

/* with j out too, every other judged sensor's leave-one-out error over the last MON_CONFIRM
   samples (their mean) within its warning band (1: too few left to judge; 0: a set the code
   does not hold) */
static int mon_resolves(const tc_state *s, int j, const int seen[], double alone) {
    double X[MW][NM], M[NM][NM], lev[NM], off = 0.0;
    int out[NM], k, r, m, n = 0, rows = mon_rows(s, X);
    for (k = 0; k < NM; k++) out[k] = k == j || mon_out_of(s, k), n += !out[k];
    if (n < MON_MIN_ACTIVE) return 1;
    if (!mon_operator(out, M, lev)) return 0;
    for (k = 0; k < NM; k++)   /* (seen: each of them still judged) */
        if (seen && seen[k] && !out[k] && (lev[k] >= MON_MAX_LEV || MON_WARN_ONLY[k])) return 0;
    for (k = 0; k < NM; k++) {
        double e = 0.0;
        if (out[k] || lev[k] >= MON_MAX_LEV || MON_WARN_ONLY[k]) continue;
        for (r = 0; r < rows; r++) e += mon_loo(M, lev, k, X[r]);
        if (!(fabs(e / rows) < s->mon_warn[k])) return 0;
    }
    if (alone < 0.0) return 1;
    for (r = 0; r < rows; r++) {   /* (alone: j off the others' field by that much at least) */
        double p = 0.0;
        for (m = 0; m < NM; m++) p += M[j][m] * X[r][m];
        off += X[r][j] - p;
    }
    return fabs(off / rows) >= alone;
}

static int mon_hovers(const tc_state *s, const int level[]);   /* (below) */

/* the served monitor's _lone_fault, every sensor in: the sensor (j: the largest |E|(1 - h), z
   its ranks) whose exclusion explains the bands, *resolves whether it does */
static int mon_lone_fault(const tc_state *s, int j, const double z[], const int level[],
                          const int jd[], int *resolves) {
    double size[NM];
    int out[NM], hidden[NM], k, i, hides, likelier = -1, done[NM], doubted;
    for (k = 0; k < NM; k++) {
        double e = mon_mean_err(s, k);
        out[k] = jd[k] && level[k] >= 1;
        size[k] = jd[k] ? fabs(isnan(e) ? 0.0 : e) : 0.0;
        done[k] = 0;
    }
    /* the likelier single fault: the largest standardised residual (mon84: asked of every
       lone fault, not only where j hides) */
    for (k = 0; k < NM; k++) {
        double w = size[k] * sqrt(fabs(1.0 - s->mon_lev[k]));
        if (likelier < 0 || w > size[likelier] * sqrt(fabs(1.0 - s->mon_lev[likelier])))
            likelier = k;
    }
    /* (mon86b: j within band, the likelier fault out of band: that one or none yet, -1;
       mon87: not where the excursion hovers, j then, held as a regime) */
    doubted = mon_resolves(s, j, level[j] < 1 ? out : 0, -1.0);
    if (doubted && !(level[j] < 1 && out[likelier] && !mon_hovers(s, level)))
        return *resolves = 1, j;
    /* (mon85: j within band hiding the likelier single fault, not its blind partner: no) */
    for (k = 0; k < NM; k++) hidden[k] = out[k] && z[k] < 0.7 * z[j] && k == likelier;
    hides = level[j] < 1 && mon_resolves(s, j, hidden, -1.0);
    for (i = 0; i < NM; i++) {   /* the others, the largest z first */
        double alone = 0.0;
        k = -1;
        for (int m = 0; m < NM; m++)
            if (!done[m] && (k < 0 || z[m] > z[k])) k = m;
        done[k] = 1;
        if (k == j || z[k] < 0 || level[k] < 1 || likelier != k) continue;
        for (int m = 0; m < NM; m++)
            if (m != k && size[m] > alone) alone = size[m];
        /* (mon84b: tested on every judged sensor, none left unjudged) */
        if (mon_resolves(s, k, jd, alone)) return *resolves = 1, k;
    }
    return doubted ? (*resolves = 1, -1) : (*resolves = hides, j);
}

/* (mon83) the served _within_rounding: sensor j's smallest error over the last MON_CONFIRM
   samples beyond the band that excludes (field) by less than its rounding bound, the memory's
   error within that of the band already, on the same side */
static int mon_within_rounding(const tc_state *s, int j, int field) {
    double least = HUGE_VAL, sum = 0.0, past = 0.0, scale[NM];
    double band = field == 1 ? s->mon_warn[j] : s->mon_alarm[j];
    int a[NM], o[NM], jd[NM], r, m;
    for (r = 0; r < MON_CONFIRM; r++) {
        double e = s->mon_err[((s->mon_pos - 1 - r) % MW + MW) % MW][j];
        if (fabs(e) < least) least = fabs(e);
        sum += e;
    }
    if (!s->mon_slow_known || !(least < band + MON_ROUNDING[j])) return 0;
    mon_set(s, a, o, jd, scale);
    for (m = 0; m < NM; m++) past += s->mon_M[j][m] * s->mon_slow[m];
    past = (s->mon_slow[j] - past) * scale[j];
    return past * (sum > 0 ? 1.0 : sum < 0 ? -1.0 : 0.0) >= band - MON_ROUNDING[j];
}

/* the served monitor's _excursion_hovers: every judged sensor out of band has an error no larger
   a share of its rise than the field's memory had (a regime, not a fault) */
static int mon_hovers(const tc_state *s, const int level[]) {
    double scale[NM], X[MW][NM];
    int a[NM], o[NM], jd[NM], k, m, r, n = 0, rows;
    if (!s->mon_slow_known || s->mon_count < 2) return 0;
    mon_set(s, a, o, jd, scale);
    mon_judging(jd);
    rows = s->mon_count < MON_CONFIRM ? s->mon_count : MON_CONFIRM;
    for (r = 0; r < rows; r++)
        for (k = 0; k < NM; k++) X[r][k] = s->mon_hist[((s->mon_pos - 1 - r) % MW + MW) % MW][k];
    for (k = 0; k < NM; k++) {
        double past = 0.0, rise = 0.0, e = mon_mean_err(s, k), sgn, then;
        if (!jd[k] || level[k] < 1) continue;
        n++;
        for (m = 0; m < NM; m++) past += s->mon_M[k][m] * s->mon_slow[m];
        past = (s->mon_slow[k] - past) * scale[k];
        for (r = 0; r < rows; r++) rise += X[r][k];
        rise = fabs(rise / rows);
        sgn = e > 0 ? 1.0 : (e < 0 ? -1.0 : (isnan(e) ? NAN : 0.0));
        then = past * sgn > 0.0 ? past * sgn * rise : 0.0 * rise;
        if (!(fabs(e) * fabs(s->mon_slow[k]) <= MON_GROWTH * then)) return 0;
    }
    return n > 0;
}

/* the served monitor's _explaining (every sensor in): a sensor no other predicts whose reading
   explains the judged sensors beyond the band (level >= field), -1: none does */
static int mon_explaining(const tc_state *s, const int level[], int field) {
    double X[MW][NM], scale[NM], z[NM], best_z = -1.0, Mu[NM][NM], lu[NM];
    int a[NM], o[NM], jd[NM], cand[NM], out[NM], k, u, r, m, best = -1, rows = mon_rows(s, X);
    mon_set(s, a, o, jd, scale);
    mon_judging(jd);
    for (k = 0; k < NM; k++) {
        double e = 0.0, h = 1.0 - s->mon_lev[k];
        z[k] = -1.0;
        if (!a[k]) continue;
        for (r = 0; r < rows; r++) {
            double p = 0.0;
            for (m = 0; m < NM; m++) p += s->mon_M[k][m] * X[r][m];
            e += X[r][k] - p;
        }
        z[k] = fabs(e / rows) / sqrt(h > 1e-12 ? h : 1e-12);
        if (jd[k] && z[k] > best_z) best_z = z[k];
    }
    for (k = 0; k < NM; k++) cand[k] = a[k] && !o[k] && !MON_WARN_ONLY[k] && z[k] > best_z;
    for (u = 0; u < NM; u++) {
        int n = 0, fails = 0;
        if (!cand[u]) continue;
        for (k = 0; k < NM; k++) n += a[k] && k != u, out[k] = !a[k] || k == u;
        if (n < MON_MIN_ACTIVE || !mon_operator(out, Mu, lu)) continue;
        for (k = 0; k < NM && !fails; k++) {
            double least = HUGE_VAL;
            int judged = a[k] && k != u && lu[k] < MON_MAX_LEV && !MON_WARN_ONLY[k];
            if (jd[k] && level[k] >= field && !judged) fails = 1;
            if (!judged) continue;
            for (r = 0; r < rows; r++) {
                double v = fabs(mon_loo(Mu, lu, k, X[r]));
                if (v < least) least = v;
            }
            if (least >= (field == 1 ? s->mon_warn[k] : s->mon_alarm[k])) fails = 1;
        }
        if (!fails && z[u] > best_z) best = u, best_z = z[u];
    }
    return best;
}

/* level[] and the judged sensors (jd[]) of the active set that judge a drift (mon_judging),
   how many are active */
static int mon_levels(const tc_state *s, int level[], int jd[]) {
    int a[NM], o[NM], k, n = 0;
    double scale[NM];
    mon_set(s, a, o, jd, scale);
    mon_judging(jd);
    for (k = 0; k < NM; k++) level[k] = jd[k] ? mon_level(s, k) : 0, n += a[k];
    return n;
}

/* judged sensors but j at least at the warning band */
static int mon_others(const int level[], const int jd[], int j) {
    int k, n = 0;
    for (k = 0; k < NM; k++) n += k != j && jd[k] && level[k] >= 1;
    return n;
}

/* j out by a drift exclusion: its return waits longer each time (served) */
static void mon_by_drift(tc_state *s, int j) {
    s->mon_by_field[j] = 1;
    s->mon_dwell[j] = MW * (1 << (s->mon_outs[j] < MON_MAX_BACKOFF ? s->mon_outs[j] : MON_MAX_BACKOFF));
    s->mon_outs[j]++;
    s->mon_since[j] = s->mon_count;
}

/* a judged sensor beyond the band (level >= field), every sensor in or (cmon85) one out: the
   culprit (the largest |E|(1 - h)) out where with it out the others are within their warning
   bands and fewer than MON_NEW_STATE_OTHERS others are out of it (else nothing: the served
   monitor's veto), its blind partner with it; flagged where the served monitor does what the
   code does not */
static void mon_drift(tc_state *s, const int level[], int field) {
    double scale[NM], z[NM], Mp[NM][NM], lp[NM];
    int a[NM], o[NM], jd[NM], lv[NM], k, j = 0, u, nblind = 0, partner = -1;
    if ((u = mon_explaining(s, level, field)) >= 0) {
        if (!MON_BLIND_OUT || (s->mon_nout > 0 && !mon_second_held(s, u))) {
            mon_flag(s, TC_MON_NOT_IN_CODE, u, TC_MON_DRIFT);
            return;
        }
        /* (cmon82c) out, held at its last reading; judged again, one beyond the alarm band
           flagged (the served monitor goes on with one out) */
        mon_put_out(s, u);
        mon_recompute(s);
        mon_by_drift(s, u);
        s->mon_explains[u] = 1;
        mon_flag(s, TC_MON_EXCLUDED, u, TC_MON_BLIND_OUT);
        if (MON_FALLBACK[u] && !MON_FALLBACK_SET[u]) s->mon_fell = 1;   /* (none in the code) */
        if (mon_levels(s, lv, jd) > MON_MIN_ACTIVE)
            for (k = 0; k < NM; k++)
                if (jd[k] && lv[k] >= 2) {
                    mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_DRIFT);
                    break;
                }
        return;
    }
    mon_set(s, a, o, jd, scale);
    mon_judging(jd);
    for (k = 0; k < NM; k++) {
        double e = mon_mean_err(s, k), sd = sqrt(fabs(1.0 - s->mon_lev[k]));
        z[k] = jd[k] ? fabs(isnan(e) ? 0.0 : e) * (sd * sd) : -1.0;
        if (z[k] > z[j]) j = k;
    }
    if (MON_NEW_STATE) {
        int resolves;
        j = mon_lone_fault(s, j, z, level, jd, &resolves);
        if (j < 0) return;   /* (mon86b) none yet */
        if (!resolves) {   /* a new thermal state (served: declared) */
            if (MON_NOVEL) s->mon_novel = 1, s->mon_calm_field = 0;
            else mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_DRIFT);
            return;
        }
        if (mon_others(level, jd, j) >= MON_NEW_STATE_OTHERS) return;
        if ((level[j] < 1 || mon_within_rounding(s, j, field)) && mon_hovers(s, level))
            return;   /* a regime, not a fault */
    }
    mon_exclude(s, j, TC_MON_DRIFT_OUT);
    if (!mon_out_of(s, j)) return;   /* (flagged) */
    mon_by_drift(s, j);
    s->mon_hid[j] = level[j] < 1;   /* (mon85b) it passed its own band */
    mon_set_bands(s);
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++)
        if (a[k] && !o[k] && !MON_WARN_ONLY[k] && z[k] >= 0.7 * z[j])
            nblind++, partner = partner < 0 ? k : partner;
    if (nblind && mon_levels(s, lv, jd) > MON_MIN_ACTIVE) {
        int out[NM];
        for (k = 0; k < NM; k++) out[k] = !a[k] || k == partner;
        /* (dep100) the partner out beside any number out, as served: no cap, the set solved */
        if (nblind > 1 || !MON_PORTED[partner] || !mon_operator(out, Mp, lp)) {
            mon_flag(s, TC_MON_NOT_IN_CODE, partner, TC_MON_DRIFT);
            return;
        }
        if (MON_NEW_STATE && !mon_resolves(s, partner, 0, -1.0)) {   /* served: declared */
            if (MON_NOVEL) s->mon_novel = 1, s->mon_calm_field = 0;
            else mon_flag(s, TC_MON_NOT_IN_CODE, partner, TC_MON_DRIFT);
            return;
        }
        if (MON_NEW_STATE && mon_others(lv, jd, partner) >= MON_NEW_STATE_OTHERS) return;
        mon_put_out(s, partner);
        mon_recompute(s);
        mon_by_drift(s, partner);
        mon_flag(s, TC_MON_EXCLUDED, partner, TC_MON_DRIFT_OUT);
    }
    if (mon_levels(s, lv, jd) > MON_MIN_ACTIVE)   /* served: judged again, a second culprit */
        for (k = 0; k < NM; k++)
            if (jd[k] && lv[k] >= 2) {
                mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_DRIFT);
                break;
            }
}

/* a self-prediction error stepped past the alarm band in one sample (the served
   _check_stepped): each such sensor fired on (instant); (cmon86) the culprit, the largest step
   times sqrt(1 - h), out as a drift exclusion is (its wait doubled, no field to follow), a
   second beside one out where the set is solved; an export before it (MON_STEPPED 0) flags it */
static void mon_stepped(tc_state *s, const double e[], int instant[]) {
    double scale[NM], best = -1.0;
    int a[NM], o[NM], jd[NM], k, j = -1, since;
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        double de = e[k] - s->mon_prev_e[k], z;
        /* (mon86) the alarm band of the set judged */
        if (!(jd[k] && fabs(e[k]) >= s->mon_alarm[k] && fabs(de) >= s->mon_alarm[k])) continue;
        if (!MON_STEPPED) {
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_STEPPED);
            return;
        }
        instant[k] = 1;
        z = fabs(de) * sqrt(fabs(1.0 - s->mon_lev[k]));
        if (z > best) best = z, j = k;
    }
    if (j < 0) return;
    mon_exclude(s, j, TC_MON_STEP_OUT);
    if (!mon_out_of(s, j)) return;   /* (flagged) */
    since = s->mon_since[j];
    mon_by_drift(s, j);
    s->mon_since[j] = since;   /* (no field follows it) */
}

/* the served monitor's exclusion by judgement where the code holds it (mon_drift), else
   flagged, none in a new thermal state (cmon82b); and a field that followed a drift exclusion
   within a window: the sensor re-admitted, a new thermal state declared (served _follow_field;
   an export before cmon82b flags it), which ends after a window with every judged sensor within
   its warning band */
static void mon_judgement(tc_state *s) {
    int level[NM], jd[NM], k, n, field = 0, leaving = 0;
    for (k = 0; k < NM; k++) field |= mon_out_of(s, k) && s->mon_by_field[k];
    field = field ? 2 : MON_EXCLUDE_LEVEL;
    n = mon_levels(s, level, jd);
    for (k = 0; k < NM && !(MON_NEW_STATE && s->mon_novel); k++)
        if (jd[k] && level[k] >= field && n > MON_MIN_ACTIVE) {
            if (!MON_DRIFT || (s->mon_nout > 0 && !MON_SOLVE))
                mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_DRIFT);
            else mon_drift(s, level, field);
            break;
        }
    if (!MON_NEW_STATE) return;
    mon_levels(s, level, jd);
    for (k = 0; k < NM; k++) {
        leaving += jd[k] && level[k] >= 1;
        if (!mon_out_of(s, k) || s->mon_count - s->mon_since[k] > MW)
            s->mon_since[k] = -1;
    }
    for (k = 0; k < NM; k++) {
        if (s->mon_since[k] < 0 || leaving < MON_NEW_STATE_OTHERS) continue;
        if (!MON_NOVEL) {
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_DRIFT);
            return;
        }
        s->mon_since[k] = -1;
        s->mon_dwell[k] = MW;
        mon_readmit(s, k, TC_MON_FOLLOWED);
        s->mon_novel = 1, s->mon_calm_field = 0;
        mon_levels(s, level, jd);
        for (leaving = 0, n = 0; n < NM; n++) leaving += jd[n] && level[n] >= 1;
    }
    s->mon_calm_field = leaving ? 0 : s->mon_calm_field + 1;
    if (s->mon_novel && s->mon_calm_field >= MW) s->mon_novel = 0;
}

/* (mon105d) until when sensor j, just out for a freeze by its run alone, is read at its held
   value (watch.py's _hold_until): its rate (least squares) over its readings within MON_TAU s
   before its run began, the drift it projects over at least that span within MON_SPREAD[j] */
static double mon_hold_until(const tc_state *s, int j) {
    double t[TC_MON_TREND], x[TC_MON_TREND], t0, tm = 0.0, xm = 0.0, sxy = 0.0, sxx = 0.0, rate;
    double first_n = s->mon_rows - s->mon_run[j];   /* the run's first reading's number */
    int first = -1, i, n = 0;
    for (i = 0; i < TC_MON_TREND; i++)   /* (dep106) the newest row kept up to it */
        if (s->mon_past_n[(s->mon_past_pos + i) % TC_MON_TREND] <= first_n) first = i;
    if (first < 2 || !(MON_SPREAD[j] > 0.0)) return -INFINITY;
    t0 = s->mon_past_t[(s->mon_past_pos + first) % TC_MON_TREND];
    for (i = 0; i <= first; i++) {   /* oldest first, to the run's first reading */
        int r = (s->mon_past_pos + i) % TC_MON_TREND;
        if (!isfinite(s->mon_past_t[r]) || !isfinite(s->mon_past[r][j])
            || !(s->mon_past_t[r] >= t0 - MON_TAU)) continue;
        t[n] = s->mon_past_t[r] - t0;
        x[n++] = s->mon_past[r][j];
    }
    if (n < 3) return -INFINITY;
    for (i = 0; i < n; i++) tm += t[i], xm += x[i];
    tm /= n, xm /= n;
    for (i = 0; i < n; i++) sxy += (t[i] - tm) * (x[i] - xm), sxx += (t[i] - tm) * (t[i] - tm);
    rate = sxx > 0.0 ? fabs(sxy / sxx) : INFINITY;
    if (!(rate * -t[0] <= MON_SPREAD[j])) return -INFINITY;
    return t0 + (rate > 0.0 ? MON_SPREAD[j] / rate : INFINITY);
}

/* one sample of the monitored inputs of u, replaced by what the model reads (the reading, or
   its POD reconstruction while it is out), as the served monitor (watch.py's slice) */
static void mon_sample(tc_state *s, double u[], double dt) {
    double x[NM], d[NM], step[NM], pred[NM], e[NM], other[NM], gap[NM], span = 1.0;
    int a[NM], o[NM], jd[NM], big[NM], same[NM], instant[NM], rng[NM], missing[NM];
    double scale[NM];
    int k, pos, nbig = 0, jumped = -1, lost = -1, far = -1, nrng = 0;
    int gone[NM], was_in[NM], fresh[NM], late[NM], nlate = 0;
    if (s->first) {
        s->mon_nout = 0;
        s->mon_pos = s->mon_count = 0;
        for (k = 0; k < NM; k++) {
            int w;
            s->mon_prev[k] = s->mon_prev_e[k] = s->mon_prev_other[k] = s->mon_run_pred[k] = NAN;
            s->mon_last_step[k] = NAN;
            s->mon_run[k] = s->mon_calm[k] = s->mon_jumps[k] = s->mon_dropped[k] = 0;
            s->mon_ranged[k] = 0;
            s->mon_froze[k] = s->mon_off[k] = 0;
            s->mon_held[k] = 0.0;
            s->mon_gap[k] = 1.0;
            s->mon_by_field[k] = s->mon_outs[k] = 0;
            s->mon_dwell[k] = MW;
            s->mon_since[k] = -1;
            s->mon_slow[k] = 0.0;
            s->mon_novel = s->mon_calm_field = s->mon_fell = 0;
            s->mon_explains[k] = s->mon_hid[k] = 0;
            s->mon_last[k] = s->mon_clean[k] = 0.0;
            s->mon_hold_to[k] = -INFINITY;
            for (w = 0; w < MW; w++) s->mon_hist[w][k] = s->mon_err[w][k] = NAN;
            for (w = 0; w < TC_MON_TREND; w++) s->mon_past[w][k] = NAN;
        }
        for (k = 0; k < TC_MON_TREND; k++) s->mon_past_t[k] = s->mon_past_n[k] = NAN;
        s->mon_past_pos = 0, s->mon_rows = 0.0;
        mon_recompute(s);   /* (every sensor in: MON_M[0]; the window all NAN) */
    }
    for (k = 0; k < NM; k++) {
        x[k] = u[TC_MONITORED[k]];   /* (NAN: missing, one mon_refuses let through) */
        missing[k] = !isfinite(x[k]);
        s->mon_read[k] = !missing[k];
        if (missing[k] && (lost < 0 || (mon_is_out(s, lost) && !mon_is_out(s, k)))) lost = k;
        rng[k] = x[k] < MON_LO_LIM[k] || x[k] > MON_HI_LIM[k];
        if (rng[k] && far < 0) far = k;
        nrng += rng[k];
        if (s->first) {   /* (dep108) beyond its range: the model reads the served stand-in (its
                             training's first reading, the campaign's A0 too), rebuilt from the
                             others while it stays beyond */
            s->mon_late[k] = rng[k] && MON_LATE;
            if (rng[k] && !MON_LATE)   /* (not in the code: the served monitor references it late) */
                mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_RANGE);
            s->mon_ref[k] = s->mon_ref0[k] = x[k];
            s->mon_base[k] = s->mon_late[k] ? MON_FIRST_C[k] : x[k];
        }
        /* (dep108f) in range again: no reference yet (served: NaN), read as no finite value
           until referenced late below */
        late[k] = !s->first && s->mon_late[k] && !missing[k] && !rng[k];
        nlate += late[k];
        d[k] = late[k] ? NAN : x[k] - s->mon_ref[k];
    }
    /* a gap in time: the step judged as that many one-sample steps, and a sensor's own
       missing samples since its last reading too */
    if (!s->first && dt > MON_GAP_PERIODS * MON_PERIOD) span = dt / MON_PERIOD > 1.0 ? dt / MON_PERIOD : 1.0;
    if (nrng && !s->first) {   /* (cmon80) beyond its range: read as missing, or as read */
        int r = mon_beyond(s, x, d, rng, nrng);
        if (r < 0) {   /* not in the code: the sample passes the monitor by, its state as it
                          was, so that the reading's return is no jump; (kelvin97) every
                          reading beyond its range: nothing to rebuild from, the model reads
                          the last field, as served; (dep98) but each step spans it, as
                          served: one beyond range a sample more of its gap, one in range
                          its last reading */
            const double *field = nrng == NM ? s->mon_last : d;
            for (k = 0; k < NM; k++) {
                double g = span > s->mon_gap[k] ? span : s->mon_gap[k];
                if (rng[k] || missing[k]) s->mon_gap[k] = g + 1.0;
                else s->mon_gap[k] = 1.0, s->mon_prev[k] = d[k];
            }
            mon_errors(s, field, pred, e);
            mon_rebuilt(s, u, field, pred);
            return;
        }
        for (far = -1, k = 0; k < NM; k++)
            if (rng[k] && far < 0) far = k;   /* (the first still read as missing) */
    }
    for (k = 0; k < NM; k++) gone[k] = missing[k] || rng[k];   /* read as missing */
    pos = s->mon_pos;
    for (k = 0; k < NM; k++) s->mon_hist[pos][k] = d[k];
    s->mon_pos = (pos + 1) % MW;
    s->mon_count++;
    for (k = 0; k < NM; k++) {
        gap[k] = (span > s->mon_gap[k]) ? span : s->mon_gap[k];
        step[k] = d[k] - s->mon_prev[k];
        big[k] = fabs(step[k]) > MON_JUMP_LIM[k] * gap[k] && !rng[k];
        same[k] = step[k] == 0.0;
        instant[k] = gone[k] || late[k];   /* (dep108f: served, a dropout's detector) */
        nbig += big[k];
    }
    if (nbig >= MON_COMMON_MIN) {   /* (cmon80) a common step re-referenced */
        mon_common_step(s, d, step, big, pos);
        for (nbig = 0, k = 0; k < NM; k++) nbig += big[k];
    }
    for (k = 0; k < NM; k++) was_in[k] = !mon_out_of(s, k);
    if (MON_BENT) {   /* (step93) a step off its own: re-referenced and kept in; a second, a jump */
        mon_bent(s, d, step, big, gone, gap, pos);
        for (nbig = 0, k = 0; k < NM; k++) nbig += big[k];
    }
    if (nbig == 1) {   /* a lone jump's change as the others see it, judged by the set in before
                          this sample's dropout or range exclusion, as served */
        mon_errors(s, d, pred, e);
        mon_set(s, a, o, jd, scale);
        for (k = 0; k < NM; k++) other[k] = jd[k] ? d[k] - e[k] : NAN;
    }
    /* (cdrop77) a missing reading: excluded, rebuilt from the others (the sensor out, missing
       again: rebuilt as it was; out for a freeze, flagged: its re-admission band is the served
       monitor's path, not held here) */
    if (lost >= 0 && mon_is_out(s, lost)) {
        if (!s->mon_dropped[lost] && !s->mon_jumps[lost])
            mon_flag(s, TC_MON_NOT_IN_CODE, lost, TC_MON_MISSING_FROZEN);
    } else if (lost >= 0) {   /* (dep101) each new one out in the monitor's order, as served */
        for (k = 0; k < NM; k++) fresh[k] = missing[k] && !mon_is_out(s, k);
        for (k = 0; k < NM; k++)
            if (fresh[k]) mon_exclude(s, k, TC_MON_DROPOUT);
    }
    for (k = 0; k < NM && far >= 0; k++)   /* (cmon80; dep99: each beyond range) */
        if (rng[k] && !mon_is_out(s, k)) mon_exclude(s, k, TC_MON_OFF_RANGE);
    if (nbig >= 2 && MON_PAIR_JUMP && lost < 0 && far < 0 && s->mon_count != 2
            && mon_pair_jump(s, x, d, step, big, instant)) {   /* (cmon93) */
        for (k = 0; k < NM; k++) s->mon_hist[pos][k] = d[k];
        nbig = 0;
    }
    for (k = 0; k < NM && nbig; k++) {
        if (!big[k]) continue;
        if (nbig > 1) mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_COMMON);
        else if (s->mon_count == 2) mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_GLITCH);
        else {
            mon_set(s, a, o, jd, scale);
            if (lost < 0 && far < 0 && !nlate && mon_spike_back(s, k, x, d, pred, a)) {   /* (mon89) */
                d[k] = x[k] - s->mon_ref[k];
                mon_readmit(s, k, TC_MON_SPIKE);
            }
            else if (a[k] && !(s->mon_nout > 0 ? mon_second_taken(s, k, TC_MON_JUMP)
                                                : MON_PORTED[k] || mon_spikes(k)))
                mon_exclude(s, k, TC_MON_JUMP);   /* flagged */
            else {   /* re-referenced by its step less its change as the others predict it */
                double expected, offset;
                if (!a[k] && !MON_PREDICTABLE[k] && !MON_BLIND_JUMP)   /* (cmon82c) the served
                                                                         return may undo it */
                    mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_BLIND);
                if (!s->mon_jumps[k]) s->mon_ref0[k] = s->mon_ref[k];
                expected = other[k] - s->mon_prev_other[k];
                offset = step[k] - (isfinite(expected) ? expected : 0.0);
                s->mon_ref[k] += offset;
                d[k] -= offset;
                jumped = k;
                s->mon_jumps[k]++;
                if (a[k]) mon_exclude(s, k, TC_MON_JUMP);
            }
            s->mon_hist[pos][k] = d[k];
        }
        break;
    }
    for (k = 0; k < NM && far >= 0; k++)   /* read as missing from here (neither a step's last
                                              reading nor in the window that decides
                                              re-admission), as served */
        if (rng[k]) d[k] = s->mon_hist[pos][k] = NAN;
    if (jumped >= 0) instant[jumped] = 1;
    for (k = 0; k < NM; k++) {
        s->mon_run[k] = same[k] ? s->mon_run[k] + 1 : 0;
        s->mon_calm[k] = instant[k] ? 0 : s->mon_calm[k] + 1;
    }
    mon_errors(s, d, pred, e);
    for (k = 0; k < NM && nlate; k++) {   /* (dep108f) the served late reference: the reading
                                             agrees with the field where the others predict it,
                                             else goes on from the value the model was given */
        int by_field;
        if (!late[k]) continue;
        by_field = MON_PREDICTABLE[k] && isfinite(pred[k]);
        d[k] = s->mon_hist[pos][k] = by_field ? pred[k] : s->mon_clean[k];
        s->mon_ref[k] = x[k] - d[k];
        e[k] = by_field ? 0.0 : NAN;
        s->mon_late[k] = 0;
    }
    for (k = 0; k < NM; k++) s->mon_err[pos][k] = e[k];
    /* freeze: constant while the field (its prediction from the others) moved by the band */
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        if (instant[k]) s->mon_froze[k] = 0;   /* another detector fired on it: out for that */
        s->mon_off[k] = s->mon_froze[k] && isfinite(d[k]) && d[k] != s->mon_held[k]
                        ? s->mon_off[k] + 1 : 0;
        other[k] = d[k] - (isfinite(e[k]) ? e[k] : d[k] - pred[k]);
        if (same[k] && s->mon_run[k] == 1) s->mon_run_pred[k] = other[k];
    }
    for (k = 0; k < NM; k++) {
        int frozen = same[k] && ((o[k] && fabs(other[k] - s->mon_run_pred[k]) >= s->mon_warn[k]
                                  && s->mon_run[k] >= MON_SEEN_RUN[k])
                                 || (!o[k] && s->mon_run[k] > MON_BLIND_RUN[k])
                                 || s->mon_run[k] > MON_DITHER_RUN[k]);
        if (!frozen || instant[k]) continue;
        instant[k] = 1;
        if (a[k]) mon_exclude(s, k, TC_MON_FREEZE);
        if (a[k] && mon_out_of(s, k)) {
            s->mon_froze[k] = 1;
            s->mon_held[k] = d[k];
            s->mon_off[k] = 0;
            /* (mon105d) never where the field moved past its band while it held */
            s->mon_hold_to[k] = o[k] && fabs(other[k] - s->mon_run_pred[k]) >= s->mon_warn[k]
                                ? -INFINITY : mon_hold_until(s, k);
        }
    }
    mon_stepped(s, e, instant);   /* (cmon86) a stepped error's culprit out */
    for (k = 0; k < NM; k++)
        if (jd[k] && mon_level(s, k)) s->mon_flags |= TC_MON_BAND;
    mon_judgement(s);   /* (cmon82) a drift exclusion */
    {   /* (freeze84) out for a freeze alone, off its held value: back at once (any out) */
        int outs[NM], i, n = s->mon_nout;
        for (i = 0; i < n; i++) outs[i] = s->mon_out_set[i];
        for (i = 0; i < n; i++) {
            k = outs[i];
            if (s->mon_count < MW || !s->mon_froze[k] || gone[k] || instant[k]
                || s->mon_off[k] < TC_MON_THAW) continue;
            if (!MON_THAWED) mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_NO_THAW);
            else {
                s->mon_froze[k] = 0;
                mon_readmit(s, k, TC_MON_THAWED);
            }
        }
    }
    if (s->mon_nout > 0 && s->mon_count >= MW) {   /* re-admission, the due sensors together */
        int due[NM], back[NM];
        for (k = 0; k < NM; k++)
            due[k] = mon_out_of(s, k) && s->mon_run[k] == 0 && !instant[k]
                     && !gone[k] && s->mon_calm[k] >= s->mon_dwell[k];
        mon_returning(s, due, back);
        for (k = 0; k < NM; k++) {
            if (!back[k]) continue;
            if (MON_BLIND_JUMP) mon_undone(s, k, d);   /* (cmon87) */
            s->mon_jumps[k] = s->mon_froze[k] = 0;
            mon_readmit(s, k, TC_MON_BACK);
        }
    }
    mon_errors(s, d, pred, e);
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        s->mon_prev_other[k] = jd[k] ? d[k] - e[k] : NAN;
        s->mon_last_step[k] = !gone[k] && gap[k] == 1.0 && !big[k] && was_in[k] && a[k]   /* (step93) */
            ? d[k] - s->mon_prev[k] : NAN;
        if (!gone[k]) s->mon_prev[k] = d[k];   /* a return is stepped from the last reading */
        s->mon_gap[k] = gone[k] ? gap[k] + 1.0 : 1.0;
        s->mon_prev_e[k] = e[k];
        if (instant[k]) s->mon_dropped[k] = missing[k];   /* the last detector to fire on it */
        if (instant[k]) s->mon_ranged[k] = rng[k];
        if (a[k] && isfinite(d[k])) s->mon_last[k] = d[k];
    }
    /* the field's memory (served: the sample folded in by its time since the last) */
    if (s->first || !isfinite(dt)) s->mon_slow_known = s->first;
    else {
        double keep = exp(-(dt > 0.0 ? dt : 0.0) / MON_TAU);
        for (k = 0; k < NM; k++)
            if (isfinite(s->mon_hist[pos][k]))
                s->mon_slow[k] = keep * s->mon_slow[k] + (1.0 - keep) * s->mon_hist[pos][k];
    }
    mon_rebuilt(s, u, d, pred);
}

/* the median of the n values v (n <= MW; v is sorted in place) */
static double mon_median(double v[], int n) {
    int i, j;
    double t;
    for (i = 1; i < n; i++) {
        for (t = v[i], j = i; j > 0 && v[j - 1] > t; j--) v[j] = v[j - 1];
        v[j] = t;
    }
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* (jump94b) before the sample x: a sensor no other predicts (MON_SETTLE_LIM finite), in or out
   for another rule than a jump, on one reference for 2 MW - 1 samples, no gap, whose window
   ending at x lies wholly off the MW before by more than MON_SETTLE_LIM: re-referenced by the
   two windows' median difference, kept in (as served: Settled._settled); (settle95) only where
   that difference passes MON_SETTLE_STEADY x the windows' larger median absolute deviation (a
   fast ramp spreads each window about as much as it parts them: not a step) */
static void mon_settled(tc_state *s, const double x[], double dt) {
    double lo1, hi1, lo2, hi2, v, sep, off, mb, mc, db, dc, b[MW], c[MW], span = 1.0, gap;
    int k, r, ok;
    if (dt > MON_GAP_PERIODS * MON_PERIOD) span = dt / MON_PERIOD > 1.0 ? dt / MON_PERIOD : 1.0;
    for (k = 0; k < NM; k++) {
        gap = span > s->mon_gap[k] ? span : s->mon_gap[k];
        if (!(MON_SETTLE_LIM[k] < HUGE_VAL) || gap != 1.0 || s->mon_settle_age[k] < 2 * MW - 1
            || (mon_is_out(s, k) && s->mon_jumps[k])) continue;
        lo1 = lo2 = HUGE_VAL;
        hi1 = hi2 = -HUGE_VAL;
        ok = isfinite(x[k] - s->mon_ref[k]);
        for (r = 0; r < 2 * MW && ok; r++) {
            v = r < 2 * MW - 1 ? s->mon_settle[r][k] : x[k] - s->mon_ref[k];
            ok = isfinite(v);
            if (r < MW) {
                b[r] = v;
                lo1 = v < lo1 ? v : lo1;
                hi1 = v > hi1 ? v : hi1;
            } else {
                c[r - MW] = v;
                lo2 = v < lo2 ? v : lo2;
                hi2 = v > hi2 ? v : hi2;
            }
        }
        sep = lo2 - hi1 > lo1 - hi2 ? lo2 - hi1 : lo1 - hi2;
        if (!ok || !(sep > MON_SETTLE_LIM[k])) continue;
        mb = mon_median(b, MW);
        mc = mon_median(c, MW);
        off = mc - mb;
        for (r = 0; r < MW; r++) {
            b[r] = fabs(b[r] - mb);
            c[r] = fabs(c[r] - mc);
        }
        db = mon_median(b, MW);
        dc = mon_median(c, MW);
        if (!(fabs(off) > MON_SETTLE_STEADY * (db > dc ? db : dc))) continue;
        s->mon_ref[k] += off;
        s->mon_prev[k] -= off;
        for (r = 0; r < MW; r++) s->mon_hist[r][k] -= off;
        if (!mon_is_out(s, k)) s->mon_last[k] -= off;
        for (r = MW; r < 2 * MW - 1; r++) s->mon_settle[r][k] -= off;
        mon_flag(s, TC_MON_REREFERENCED, k, TC_MON_SETTLED);
    }
}

/* (wires100) the monitored readings of u as read from two wires exchanged, as served
   (InstantFaults._exchanged): every sensor in and read, exactly two flagged at one sample (a step
   past the jump limit times the samples it spans, or a reading beyond range), each reading within
   the OTHER's jump limit of the reading the sensors without both predict for the other (its last
   reading where no other predicts it): read exchanged from that sample on (mon_perm), flagged
   REREFERENCED / WIRES_EXCHANGED on the first of the two (mon_perm names the other).  A set the
   code cannot solve: flagged NOT_IN_CODE, read as before.  u's monitored inputs in mon_perm's
   order after it */
static void mon_exchange(tc_state *s, double u[], double dt) {
    double x[NM], d[NM], lim[NM], seen[NM], change[NM], g;
    int k, out[NM], nflag = 0, i = -1, j = -1;
    if (s->first) {
        for (k = 0; k < NM; k++) s->mon_perm[k] = k;
        return;
    }
    for (k = 0; k < NM; k++) x[k] = u[TC_MONITORED[s->mon_perm[k]]];
    if (MON_EXCHANGE && s->mon_nout == 0 && s->mon_count > 0) {
        for (k = 0; k < NM; k++) {
            g = s->mon_gap[k];
            if (dt > MON_GAP_PERIODS * MON_PERIOD && dt / MON_PERIOD > g) g = dt / MON_PERIOD;
            if (g < 1.0) g = 1.0;
            d[k] = x[k] - s->mon_ref[k];
            lim[k] = MON_JUMP_LIM[k] * g;
            out[k] = fabs(d[k] - s->mon_prev[k]) > lim[k] || x[k] < MON_LO_LIM[k]
                     || x[k] > MON_HI_LIM[k];
            if (!isfinite(d[k] - s->mon_prev[k])) nflag = NM + 1;
            if (out[k]) {
                if (i < 0) i = k; else j = k;
                nflag++;
            }
        }
        if (nflag == 2) {
            if (!mon_change_seen(s, d, out, out, change)) {
                mon_flag(s, TC_MON_NOT_IN_CODE, i, TC_MON_WIRES_EXCHANGED);
            } else {
                for (k = 0; k < NM; k++)
                    seen[k] = s->mon_ref[k] + s->mon_prev[k] + (isfinite(change[k]) ? change[k] : 0.0);
                if (fabs(x[j] - seen[i]) < lim[i] && fabs(x[i] - seen[j]) < lim[j]) {
                    int t = s->mon_perm[i];
                    s->mon_perm[i] = s->mon_perm[j];
                    s->mon_perm[j] = t;
                    mon_flag(s, TC_MON_REREFERENCED, i, TC_MON_WIRES_EXCHANGED);
                    g = x[i], x[i] = x[j], x[j] = g;
                }
            }
        }
    }
    for (k = 0; k < NM; k++) u[TC_MONITORED[k]] = x[k];
}

/* one sample of the monitored inputs of u, replaced by what the model reads (the reading, or
   its POD reconstruction while it is out), as the served monitor (watch.py's slice); (jump94b)
   a blind sensor's settled level shift judged before it, its ring of readings after */
static void monitor_sample(tc_state *s, double u[], double dt);

static void monitor_step(tc_state *s, double u[], double dt, double now) {
    s->mon_now = now;
    monitor_sample(s, u, dt);
    {   /* (mon105d) the row kept, as the served update keeps it; (dep106) one a step of time */
        int k, p = s->mon_past_pos;
        double step = MON_TAU / TC_MON_HALF;
        if (!(floor(now / step) == floor(s->mon_past_t[(p + TC_MON_TREND - 1) % TC_MON_TREND] / step))) {
            for (k = 0; k < NM; k++) s->mon_past[p][k] = s->mon_hist[(s->mon_pos + MW - 1) % MW][k];
            s->mon_past_t[p] = now, s->mon_past_n[p] = s->mon_rows;
            s->mon_past_pos = (p + 1) % TC_MON_TREND;
        }
        s->mon_rows += 1.0;
    }
}

/* monitor_step's sample (mon105d: monitor_step keeps its row and time after it) */
static void monitor_sample(tc_state *s, double u[], double dt) {
    double x[NM], ref[NM];
    int k, r, count = s->mon_count;
    mon_clear(s);
    mon_exchange(s, u, dt);
    if (!MON_SETTLED) {
        mon_sample(s, u, dt);
        return;
    }
    for (k = 0; k < NM; k++) x[k] = u[TC_MONITORED[k]];
    if (s->first)
        for (k = 0; k < NM; k++) {
            s->mon_settle_age[k] = 0;
            for (r = 0; r < 2 * MW - 1; r++) s->mon_settle[r][k] = NAN;
        }
    else
        mon_settled(s, x, dt);
    for (k = 0; k < NM; k++) ref[k] = s->mon_ref[k];
    mon_sample(s, u, dt);
    for (k = 0; k < NM; k++) {
        s->mon_settle_age[k] = s->first || !(fabs(s->mon_ref[k] - ref[k]) <= 1e-12)
            ? 1 : s->mon_settle_age[k] + 1;
        for (r = 0; r < 2 * MW - 2; r++) s->mon_settle[r][k] = s->mon_settle[r + 1][k];
        /* the sample as read, NAN beyond range; (dep98) of one that passed the monitor by too
           (its window untouched), as served: the window's last row again read a unit's
           return (K -> degC) as a settled step */
        s->mon_settle[2 * MW - 2][k] = s->first || s->mon_count != count
            ? s->mon_hist[(s->mon_pos + MW - 1) % MW][k]
            : (x[k] < MON_LO_LIM[k] || x[k] > MON_HI_LIM[k] ? NAN : x[k] - s->mon_ref[k]);
    }
}

#undef NM
#undef MW
"""
