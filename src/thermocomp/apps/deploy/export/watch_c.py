"""The code's sensor monitor (:mod:`.watch`) in C: its constants, its part of ``tc_state`` and
``monitor_step``, which ``tc_step`` calls on each sample after the time rule (cmon76)."""

from __future__ import annotations

from .watch import BAND, EXCLUDED, NOT_IN_CODE, OUT, READMITTED, REASONS, REREFERENCED, RULES


def header_part(ss) -> str:
    """The defines, the reasons and the monitored inputs (``compensator.h``, before the state)."""
    m = ss.monitor
    n = len(m.get("inputs", []))
    reasons = ", ".join(f'"{r}"' for r in REASONS)        # (plain ASCII, no quote in them)
    rules = "\n".join(f"#define TC_MON_{name} {k}" for k, name in enumerate(RULES) if k)
    return f"""#define TC_MONITOR {int(bool(m))}   /* the sensor monitor in the code (docs/monitoring.md) */
#define TC_N_MONITORED {n}
#define TC_MON_WINDOW {max(int(m.get("window", 1)), 1)}
/* tc_state.mon_flags, per sample: a sensor excluded, re-admitted, one out (the model reads its
   reconstruction), a judged sensor beyond its warning band, a rule of the served monitor that
   is not in the code fired (from here the code may part from the served model), and sensors
   re-referenced by a common step (cmon80) */
#define TC_MON_EXCLUDED {EXCLUDED}
#define TC_MON_READMITTED {READMITTED}
#define TC_MON_OUT {OUT}
#define TC_MON_BAND {BAND}
#define TC_MON_NOT_IN_CODE {NOT_IN_CODE}
#define TC_MON_REREFERENCED {REREFERENCED}
/* tc_state.mon_rule indexes these (0: none); tc_state.mon_sensor the monitored sensor k, the
   input TC_MONITORED[k] */
{rules}
static const char *const TC_MONITOR_REASONS[{len(REASONS)}] = {{{reasons}}};
static const int TC_MONITORED[{max(n, 1)}] = {{{", ".join(str(i) for i in m.get("inputs", [])) or "0"}}};
"""


STATE = """    /* the sensor monitor (TC_MONITOR): referenced readings d = u - mon_ref of the monitored
       inputs, their self-prediction errors over the last TC_MON_WINDOW samples (a ring) */
    double mon_ref[NM], mon_base[NM], mon_prev[NM], mon_prev_e[NM], mon_prev_other[NM];
    double mon_hist[TC_MON_WINDOW][NM], mon_err[TC_MON_WINDOW][NM], mon_run_pred[NM];
    int mon_run[NM], mon_calm[NM], mon_pos, mon_count;
    /* (cdrop77) samples the next step spans (1 + its missing ones, or a gap in time), jumps
       re-referenced since it was last in, out for a dropout (its re-admission band) */
    double mon_gap[NM];
    int mon_jumps[NM], mon_dropped[NM];
    int mon_out;                                /* the sensor out (-1: none) */
    int mon_flags, mon_sensor, mon_rule;        /* the last sample's (TC_MON_*) */
"""


def state_part(ss) -> str:
    return STATE.replace("NM", str(max(len(ss.monitor.get("inputs", [])), 1)))


def monitor_arrays(ss) -> list[tuple[str, object, tuple, str]]:
    """The monitor's constants as :func:`.c._declared` takes them (zeros where there is none)."""
    m = ss.monitor
    n = len(m.get("inputs", []))
    vectors = ("warning", "alarm", "jump_lim", "lo_lim", "hi_lim", "lo_c", "hi_c", "seen_run",
               "blind_run")
    scalars = (("MON_MAX_LEV", "max_leverage", 1.0, "real"), ("MON_MIN_ACTIVE", "min_active", 0, "int"),
               ("MON_CONFIRM", "confirm", 1, "int"), ("MON_EXCLUDE_LEVEL", "exclude_level", 1, "int"),
               ("MON_PERIOD", "period", 1.0, "real"), ("MON_GAP_PERIODS", "gap_periods", 1.5, "real"),
               ("MON_READMIT", "readmit", 0.5, "real"), ("MON_COMMON_MIN", "common_min", 3, "int"),
               ("MON_COMMON_SPREAD", "common_spread", 2.0, "real"))
    return [("MON_M", m.get("M", []), (n + 1, n, n), "real"),
            ("MON_LEV", m.get("lev", []), (n + 1, n), "real"),
            *((f"MON_{k.upper()}", m.get(k, [0.0] * n), (n,), "real") for k in vectors),
            ("MON_PREDICTABLE", m.get("predictable", []), (n,), "int"),
            ("MON_PORTED", m.get("ported_out", []), (n,), "int"),
            *((name, m.get(key, default), (), kind) for name, key, default, kind in scalars)]


FUNCTIONS = r"""
#define NM (TC_N_MONITORED > 0 ? TC_N_MONITORED : 1)   /* (no monitor: never called) */
#define MW TC_MON_WINDOW
/* the active set (mon_out: -1 every sensor in, j sensor j out): which sensors are in, judged
   (the others predict them) and each error's scale 1 / (1 - h) (an active one no other
   predicts: NAN, not judged) */
static void mon_set(const tc_state *s, int active[], int observable[], int judged[], double scale[]) {
    int k;
    for (k = 0; k < NM; k++) {
        double lev = MON_LEV[s->mon_out + 1][k];
        active[k] = k != s->mon_out;
        observable[k] = lev < MON_MAX_LEV;
        judged[k] = active[k] && observable[k];
        scale[k] = judged[k] ? 1.0 / (1.0 - lev > 1e-12 ? 1.0 - lev : 1e-12) : (active[k] ? NAN : 1.0);
    }
}

/* each sensor's prediction from the active ones (the POD operator of the set) and its error */
static void mon_errors(const tc_state *s, const double d[], double pred[], double e[]) {
    int a[NM], o[NM], jd[NM], k, m;
    double scale[NM];
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        pred[k] = 0.0;
        for (m = 0; m < NM; m++) pred[k] += MON_M[s->mon_out + 1][k][m] * (isfinite(d[m]) ? d[m] : 0.0);
        e[k] = (d[k] - pred[k]) * scale[k];
    }
}

/* the window's errors redone under a new operator (an exclusion, a re-admission) */
static void mon_recompute(tc_state *s) {
    double pred[NM];
    int w;
    for (w = 0; w < MW; w++) {
        double e[NM];
        int k;
        mon_errors(s, s->mon_hist[w], pred, e);
        for (k = 0; k < NM; k++) s->mon_err[w][k] = e[k];
    }
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
    return (a >= MON_WARNING[k]) + (a >= MON_ALARM[k]);
}

static void mon_flag(tc_state *s, int bit, int k, int rule) {
    s->mon_flags |= bit;
    if (!s->mon_rule) s->mon_sensor = k, s->mon_rule = rule;   /* the sample's first event */
}

/* sensor k out where the code holds it (one out, the others predicting it); else flagged */
static void mon_exclude(tc_state *s, int k, int rule) {
    if (s->mon_out >= 0 || !MON_PORTED[k]) {
        mon_flag(s, TC_MON_NOT_IN_CODE, k, s->mon_out >= 0 ? TC_MON_SECOND : TC_MON_BLIND);
        return;
    }
    s->mon_out = k;
    s->mon_calm[k] = 0;
    mon_recompute(s);
    mon_flag(s, TC_MON_EXCLUDED, k, rule);
}

/* re-admission: sensor k's leave-one-out error with every sensor in, over the whole window,
   within MON_READMIT of its warning band (one out for a dropout alone: its whole band) */
static int mon_passes(const tc_state *s, int k) {
    double worst = 0.0, lev = MON_LEV[0][k];
    double band = (s->mon_dropped[k] && !s->mon_jumps[k]) ? 1.0 : MON_READMIT;
    int w, m;
    if (NM < MON_MIN_ACTIVE) return 0;
    if (lev >= MON_MAX_LEV) return !MON_PREDICTABLE[k];
    for (w = 0; w < MW; w++) {
        double p = 0.0, v;
        for (m = 0; m < NM; m++)
            p += MON_M[0][k][m] * (isfinite(s->mon_hist[w][m]) ? s->mon_hist[w][m] : 0.0);
        v = fabs(((isfinite(s->mon_hist[w][k]) ? s->mon_hist[w][k] : 0.0) - p) / (1.0 - lev));
        if (v > worst) worst = v;
    }
    return worst < band * MON_WARNING[k];
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
    int k, j = -1, nnew = 0, miss = -1, rng = 0, rule = 0;
    s->mon_flags = s->mon_rule = 0;
    s->mon_sensor = -1;
    for (k = 0; k < TC_N_MONITORED; k++) {
        double x = u[TC_MONITORED[k]];
        if (!measured(u, TC_MONITORED[k])) {
            if (miss < 0) miss = k;
            if (s->first || k != s->mon_out) {
                if (j < 0) j = k;
                nnew++;
            }
        } else if (x < MON_LO_LIM[k] || x > MON_HI_LIM[k]) rng = 1;
    }
    if (miss < 0) return 0;
    if (s->first) rule = TC_MON_MISSING_FIRST;
    else if (nnew > 1 || (nnew && (s->mon_out >= 0 || rng))) rule = TC_MON_MISSING_SECOND;
    else if (nnew && !MON_PORTED[j]) rule = TC_MON_MISSING_BLIND;
    if (rule) mon_flag(s, TC_MON_NOT_IN_CODE, j >= 0 ? j : miss, rule);
    return rule;
}

/* the monitored inputs of u as the model reads them: the reading, the sensor out rebuilt */
static void mon_rebuilt(tc_state *s, double u[], const double d[], const double pred[]) {
    int k;
    for (k = 0; k < NM; k++) u[TC_MONITORED[k]] = s->mon_base[k] + (k == s->mon_out ? pred[k] : d[k]);
    if (s->mon_out >= 0) s->mon_flags |= TC_MON_OUT;
}

/* (cmon80) a reading beyond its range (rng: which, nrng of them) after a campaign's first
   sample: 1 read as missing, 0 read (the others predict it beyond the same training edge by
   more than its warning band and it reads nearer that than half its distance from the edge: a
   machine hotter than training), -1 not in the code (flagged): several at once, one with
   another sensor out, one of a sensor the code does not hold out */
static int mon_beyond(tc_state *s, const double x[], const double d[], int j, int nrng) {
    int m;
    if (nrng > 1 || (s->mon_out >= 0 && j != s->mon_out)) {
        mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_RANGE);
        return -1;
    }
    if (j == s->mon_out) return 1;   /* out already: read as missing */
    if (NM - 1 >= MON_MIN_ACTIVE) {   /* predicted from the others, all within range */
        double p = 0.0, edge;
        int up = x[j] > MON_HI_C[j], beyond;
        for (m = 0; m < NM; m++) p += MON_M[j + 1][j][m] * (m == j ? 0.0 : d[m]);
        p += x[j] - d[j];
        edge = up ? MON_HI_C[j] : MON_LO_C[j];
        beyond = (up ? p - edge : edge - p) > MON_WARNING[j];
        if (beyond && fabs(x[j] - p) < 0.5 * fabs(x[j] - edge)) return 0;
    }
    if (!MON_PORTED[j]) {
        mon_flag(s, TC_MON_NOT_IN_CODE, j, TC_MON_BLIND);
        return -1;
    }
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
        took[k] = k != s->mon_out && r >= 1.0 / MON_COMMON_SPREAD && r <= MON_COMMON_SPREAD;
        ntook += took[k];
        njump += took[k] && big[k];
        nread += k != s->mon_out && isfinite(d[k]);
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

/* one sample of the monitored inputs of u, replaced by what the model reads (the reading, or
   its POD reconstruction while it is out), as the served monitor (watch.py's slice) */
static void monitor_step(tc_state *s, double u[], double dt) {
    double x[NM], d[NM], step[NM], pred[NM], e[NM], other[NM], gap[NM], span = 1.0;
    int a[NM], o[NM], jd[NM], big[NM], same[NM], instant[NM], rng[NM], missing[NM];
    double scale[NM];
    int k, pos, nbig = 0, jumped = -1, field = 0, nactive = 0, lost = -1, far = -1, nrng = 0;
    int gone[NM];
    if (s->first) {
        s->mon_out = -1;
        s->mon_pos = s->mon_count = 0;
        for (k = 0; k < NM; k++) {
            int w;
            s->mon_prev[k] = s->mon_prev_e[k] = s->mon_prev_other[k] = s->mon_run_pred[k] = NAN;
            s->mon_run[k] = s->mon_calm[k] = s->mon_jumps[k] = s->mon_dropped[k] = 0;
            s->mon_gap[k] = 1.0;
            for (w = 0; w < MW; w++) s->mon_hist[w][k] = s->mon_err[w][k] = NAN;
        }
    }
    s->mon_flags = s->mon_rule = 0;
    s->mon_sensor = -1;
    for (k = 0; k < NM; k++) {
        x[k] = u[TC_MONITORED[k]];   /* (NAN: missing, one mon_refuses let through) */
        missing[k] = !isfinite(x[k]);
        if (missing[k] && lost < 0) lost = k;
        rng[k] = x[k] < MON_LO_LIM[k] || x[k] > MON_HI_LIM[k];
        if (rng[k] && far < 0) far = k;
        nrng += rng[k];
        if (rng[k] && s->first)   /* (not in the code: the served monitor references it late) */
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_RANGE);
        if (s->first) s->mon_ref[k] = s->mon_base[k] = x[k];
        d[k] = x[k] - s->mon_ref[k];
    }
    if (nrng && !s->first) {   /* (cmon80) beyond its range: read as missing, or as read */
        int r = mon_beyond(s, x, d, far, nrng);
        if (r < 0) {   /* not in the code: the sample passes the monitor by, its state as it
                          was, so that the reading's return is no jump */
            mon_errors(s, d, pred, e);
            mon_rebuilt(s, u, d, pred);
            return;
        }
        if (!r) rng[far] = 0, far = -1;
    }
    for (k = 0; k < NM; k++) gone[k] = missing[k] || rng[k];   /* read as missing */
    pos = s->mon_pos;
    for (k = 0; k < NM; k++) s->mon_hist[pos][k] = d[k];
    s->mon_pos = (pos + 1) % MW;
    s->mon_count++;
    /* a gap in time: the step judged as that many one-sample steps, and a sensor's own
       missing samples since its last reading too */
    if (!s->first && dt > MON_GAP_PERIODS * MON_PERIOD) span = dt / MON_PERIOD > 1.0 ? dt / MON_PERIOD : 1.0;
    for (k = 0; k < NM; k++) {
        gap[k] = (span > s->mon_gap[k]) ? span : s->mon_gap[k];
        step[k] = d[k] - s->mon_prev[k];
        big[k] = fabs(step[k]) > MON_JUMP_LIM[k] * gap[k] && !rng[k];
        same[k] = step[k] == 0.0;
        instant[k] = gone[k];
        nbig += big[k];
    }
    if (nbig >= MON_COMMON_MIN) {   /* (cmon80) a common step re-referenced */
        mon_common_step(s, d, step, big, pos);
        for (nbig = 0, k = 0; k < NM; k++) nbig += big[k];
    }
    /* (cdrop77) a missing reading: excluded, rebuilt from the others (the sensor out, missing
       again: rebuilt as it was; out for a freeze, flagged: its re-admission band is the served
       monitor's path, not held here) */
    if (lost >= 0) {
        if (lost != s->mon_out) mon_exclude(s, lost, TC_MON_DROPOUT);
        else if (!s->mon_dropped[lost] && !s->mon_jumps[lost])
            mon_flag(s, TC_MON_NOT_IN_CODE, lost, TC_MON_MISSING_FROZEN);
    }
    if (far >= 0 && far != s->mon_out) mon_exclude(s, far, TC_MON_OFF_RANGE);   /* (cmon80) */
    for (k = 0; k < NM && nbig; k++) {
        if (!big[k]) continue;
        if (nbig > 1) mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_COMMON);
        else if (s->mon_count == 2) mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_GLITCH);
        else {
            mon_set(s, a, o, jd, scale);
            if (a[k] && (s->mon_out >= 0 || !MON_PORTED[k])) mon_exclude(s, k, TC_MON_JUMP);   /* flagged */
            else {   /* re-referenced by its step less its change as the others predict it */
                double expected, offset;
                mon_errors(s, d, pred, e);
                expected = (jd[k] ? d[k] - e[k] : NAN) - s->mon_prev_other[k];
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
    if (far >= 0) {   /* read as missing from here (neither a step's last reading nor in the
                         window that decides re-admission), as served */
        d[far] = NAN;
        s->mon_hist[pos][far] = NAN;
    }
    if (jumped >= 0) instant[jumped] = 1;
    for (k = 0; k < NM; k++) {
        s->mon_run[k] = same[k] ? s->mon_run[k] + 1 : 0;
        s->mon_calm[k] = instant[k] ? 0 : s->mon_calm[k] + 1;
    }
    mon_errors(s, d, pred, e);
    for (k = 0; k < NM; k++) s->mon_err[pos][k] = e[k];
    /* freeze: constant while the field (its prediction from the others) moved by the band */
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        other[k] = d[k] - (isfinite(e[k]) ? e[k] : d[k] - pred[k]);
        if (same[k] && s->mon_run[k] == 1) s->mon_run_pred[k] = other[k];
    }
    for (k = 0; k < NM; k++) {
        int frozen = same[k] && ((o[k] && fabs(other[k] - s->mon_run_pred[k]) >= MON_WARNING[k]
                                  && s->mon_run[k] >= MON_SEEN_RUN[k])
                                 || (!o[k] && s->mon_run[k] > MON_BLIND_RUN[k]));
        if (!frozen || instant[k]) continue;
        instant[k] = 1;
        if (a[k]) mon_exclude(s, k, TC_MON_FREEZE);
    }
    /* rules not in the code: a stepped error, a drift beyond the band (their exclusion) */
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        nactive += a[k];
        if (jd[k] && fabs(e[k]) >= MON_ALARM[k] && fabs(e[k] - s->mon_prev_e[k]) >= MON_ALARM[k])
            mon_flag(s, TC_MON_NOT_IN_CODE, k, TC_MON_STEPPED);
    }
    for (k = 0; k < NM; k++) {
        int level = jd[k] ? mon_level(s, k) : 0;
        if (level) s->mon_flags |= TC_MON_BAND;
        if (level >= MON_EXCLUDE_LEVEL && !field) field = k + 1;
    }
    if (field && nactive > MON_MIN_ACTIVE) mon_flag(s, TC_MON_NOT_IN_CODE, field - 1, TC_MON_DRIFT);
    k = s->mon_out;
    if (k >= 0 && s->mon_count >= MW && s->mon_run[k] == 0 && !instant[k] && !gone[k]
        && s->mon_calm[k] >= MW && mon_passes(s, k)) {
        s->mon_out = -1;
        s->mon_jumps[k] = 0;
        mon_recompute(s);
        mon_flag(s, TC_MON_READMITTED, k, TC_MON_BACK);
    }
    mon_errors(s, d, pred, e);
    mon_set(s, a, o, jd, scale);
    for (k = 0; k < NM; k++) {
        s->mon_prev_other[k] = jd[k] ? d[k] - e[k] : NAN;
        if (!gone[k]) s->mon_prev[k] = d[k];   /* a return is stepped from the last reading */
        s->mon_gap[k] = gone[k] ? gap[k] + 1.0 : 1.0;
        s->mon_prev_e[k] = e[k];
        if (instant[k]) s->mon_dropped[k] = missing[k];   /* the last detector to fire on it */
    }
    mon_rebuilt(s, u, d, pred);
}
#undef NM
#undef MW
"""
