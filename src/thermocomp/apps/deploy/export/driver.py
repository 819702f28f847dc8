"""``stream.c``, the exported C code's CSV driver: rows of raw inputs on stdin, the corrections
on stdout, the lab's own file as it is written (its headers, separator, decimal commas, run
column and wall-clock times: ``docs/to-the-machine.md``).  The same text for every model: what
differs (the names, the run column) is in ``compensator.h`` (:mod:`.c`)."""

DRIVER = r"""/* stream.c: CSV rows of raw inputs on stdin -> corrections C_<axis> in um as CSV on stdout.
 *
 * The header names the columns (any order, extra columns ignored) by their contract names or
 * by the lab's headers the model was made from (TC_LAB_NAMES: `T0 [degC]` for T_T0, `Zeit [s]`
 * for time); every input of TC_INPUT_NAMES is needed, `time` when the model reads it.  A column
 * under a lab's header in another unit (`T0 [degF]`, `T1 [K]`, `dX [mm]`, `Zeit [min]`, or a
 * unit data.units gave it) is converted cell by cell as the model's reader converted it
 * (TC_LAB_UNITS: value * scale + offset, to degC, um, s); under its contract name a column is in
 * the contract's unit.  The corrections printed are in um (an angular error's, a tilt, in
 * um/m = urad: iso67).  The
 * separator is the header's: ';', a tab or '|' where it holds one, else ','; with another
 * separator than ',' a decimal comma reads (12,5).  The time is seconds, or a logger's
 * wall-clock time (ISO 8601 2023-01-07T08:45:00, a zone offset or none; day-first
 * 07.01.2023 08:45:00, or 07.01.23 08:45 with a two-digit year; with TC_SLASHED a date with
 * slashes in data.time's order, a Keysight DAQ's 03/01/2027 06:00:00:011, its ms after a
 * colon: keysight70; 12 or 14 digits that are a date and time, an AmeriFlux table's
 * 202503272330: realexport73) read as seconds since the
 * campaign's first, as the served model reads it; every time of a stream in the form of its
 * first; with TC_ELAPSED (data.time=elapsed) a logger's h:mm:ss since the start, 59:59:00.5.
 * A cell that is no number (a time of day alone, 08:45:00) is refused with its row.
 * A blank row whose next row has no time or one not after the last (dep107b: within a run, its
 * time going on, a blank row is nothing, as run and replay read it; dep108b: in a stream without
 * a time column nothing, said, as the file reader says it), a `reset` column holding 1,
 * a new value in the run-number column
 * TC_RUN_COLUMN, or a time more than TC_PAUSE_S after the last (data.runs_at_pauses: a lab's
 * tests appended in one file, catman70) starts a campaign (the row is its reference).  With
 * TC_ADAPT, a row carrying a measured error in a TC_ERROR_NAMES column (E_<axis>, optional;
 * blank: none) is a reference measurement: its correction is printed, then the bias learns;
 * a target derived from error columns (data.derive) is measured where the row carries its
 * TC_SOURCE_NAMES columns, by the reader's arithmetic (TC_DERIVED_REFERENCE).
 * With `--state FILE` a restarted process goes on where the last one stopped: FILE, where it
 * exists, is read back at the start (the compensator's tc_state, the stream's clock and its
 * run), and written after every row (to FILE.tmp, then renamed over FILE: a process killed
 * mid-write leaves the previous row's state); a FILE of another build is refused.
 * A logger's preamble above the header (`Machine;PM-12`, `Operator: ...`: at most MAX_PREAMBLE
 * lines) is skipped as the model's reader skips it: the header is the first line naming every
 * input, alone or with the unit row under it.  A unit row under the header (`;;degC;W;um`) is
 * left out, each header read with its unit (`T Halle [degC]`; a name then still written twice
 * numbered as the reader numbers it: `T;T` over `degC;K` is `T [degC]`, `T [K]`; `Temp;Temp`
 * over `degC;degC` is `Temp [degC]`, `Temp#2 [degC]`), and rows under them that describe the
 * channels before the first sample (catman70: HBM catman's row of channel comments, its T0 / dt
 * rows) are left out as the reader leaves them out; a line in data.encoding (TC_ENCODING: a
 * Windows logger's cp1252) is read as UTF-8 (a line that is UTF-8 already as it is); the header
 * written again further down (a logger restarted), with its unit row, is left out and said; a
 * cell holding a mark of
 * data.missing_values (TC_MISSING: `---`; TC_MISSING_VALUE: -9999 however written) or an
 * infinite reading (`INF`, `-INF`, `Infinity`) is a missing value, as an empty cell is, and a cell
 * of an input that is no number nor a mark is refused with its row, as the reader refuses it.
 * A missing value of an input is refused (exit 2, naming the line and the input), but (cdrop77)
 * with TC_MONITOR one of a monitored sensor (TC_MONITORED) its monitor rebuilds, said on stderr
 * (`line 22: monitor: T_b: dropout: no finite value, excluded`); where it cannot (a campaign's
 * first row, another sensor out or missing, one it does not hold out) the row is refused.
 * UTF-16 text with its byte-order mark, little- or big-endian (catman AP's or Excel's Unicode
 * export) is read as its UTF-8 text (transcoded here; data.encoding does not apply to it), as
 * the model's reader reads it; two bytes that are no UTF-16 character (a lone surrogate, an odd
 * byte at the end) are refused with their line.
 * A file in fixed-width columns, JSON Lines, UTF-32 text, a TDMS log or a MATLAB file is
 * refused: convert
 * it to CSV first (the export's check/<campaign>/rows.csv holds such a record's rows as this
 * reads them).
 * With `--check FILE` (a pack's check/<campaign>/expected.csv, export writes them with the
 * rows.csv each holds) every row of corrections is compared with FILE's as it is printed:
 * the first farther than CHECK_UM + CHECK_RELATIVE * |expected| (`--tolerance UM`, `--relative
 * R` to change them) is named on stderr, exit 1; within it, the largest difference is said.
 * A model that reads no ambient sensor and picks its laws by a campaign's initial ambient
 * (TC_AMBIENT_GIVEN: the manifest's ambient_c) takes it from an `ambient_c` column (degC, its
 * value on a campaign's first row; the pack's rows.csv carry it), else from `--ambient C`.
 * (extension, cflags100) With `--flags` each row carries, after the corrections, the code's sensor
 * monitor's state at that sample (tc_state.mon_flags): one 0/1 column per flag kind
 * (TC_FLAG_NAMES: mon_excluded, mon_readmitted, mon_out, mon_band, mon_not_in_code,
 * mon_rereferenced, mon_new_state) and excluded_inputs, the monitored sensors out in the order
 * they went out, ';' between them (the served model's column of that name, which joins by ',').
 * (extension, cin103) then time_read, what the row's time was taken as (the served model's
 * `time` events): 0 read as given; 1 no time (an empty cell) and 2 a time not after the last one
 * read, each taken one period after the previous row (served: `ok -> substituted` at the row it
 * sets in, `substituted -> ok` at the row it ends); 3 a row written again, skipped (served:
 * `repeated`).
 * (extension, packflags100) With `--check-flags FILE` (a pack's check/<campaign>/flags.csv, export
 * writes it beside expected.csv where the code holds the monitor) each row's flags as `--flags`
 * prints them are compared with FILE's: the first row that differs is named on stderr with the
 * flag and both values, exit 1.
 * Build: cc compensator.c stream.c -lm -o stream
 * Run:   ./stream [--state FILE] [--check FILE [--tolerance UM] [--relative R]]
 *                 [--check-flags FILE] [--ambient C] [--flags] < rows.csv
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "compensator.h"

#define MAX_LINE 65536
#define MAX_PREAMBLE 20   /* lines above the header, as the model's reader allows */
#define MAX_PROPERTY_ROWS 6   /* rows describing the channels under the header, likewise */
#define MAX_COLS 1024
#define MAX_CELL 256
/* (lab78) what converts a lab's file the stream does not read (a Scope export, a TDMS log, JSON
   Lines, ...) into its rows, under the names the model reads: the data config it was fitted with */
#define ROWS_COMMAND "`thermocomp rows FILE [its data config: data=<name> that thermocomp init " \
    "wrote, data.*] > rows.csv` (thermocomp's venv), then stream rows.csv"
#define CHECK_UM 1e-9          /* --check: |c - expected| <= CHECK_UM + CHECK_RELATIVE * |expected| */
#define CHECK_RELATIVE 1e-9    /* (float64 in another order: check/check.json says why) */

enum { SECONDS = 1, LOCAL_TIME, ZONED_TIME };   /* a stream's time: as its first is written */

static char sep = ',';

/* A line's cells at `by`; a separator inside double quotes is the cell's, as a CSV reader
   reads it (stranger65: a spreadsheet's "1,200.0" in a ','-separated file split a row in two
   cells, "row has not 14 cells", though the model reads no such column). */
static int split_by(char *line, char **cells, char by) {
    int n = 0, quoted = 0;
    char *p = line;
    line[strcspn(line, "\r\n")] = '\0';
    cells[n++] = p;
    for (; *p && n < MAX_COLS; p++) {
        if (*p == '"') quoted = !quoted;
        else if (*p == by && !quoted) { *p = '\0'; cells[n++] = p + 1; }
    }
    return n;
}

static int split(char *line, char **cells) { return split_by(line, cells, sep); }

static char *twin(char **raw, int j);
static int unit_named(char **raw, int ncols, const char *line, const char **names);

/* Each column's conversion to the contract's unit: value * scale + offset (TC_LAB_UNITS). */
static double scale_of[MAX_COLS], offset_of[MAX_COLS];

/* A header cell as named: without spaces and quotes around it, read as its contract name;
   column j's conversion set from the lab's header (1 and 0 under a contract name). */
/* The contract name of the lab's header `cell` (exactly as written), its unit's scale and offset
   set for column j; NULL where the model's data names no such header. */
static int lab_index(const char *cell) {
    int k;
    for (k = 0; k < TC_N_LAB_NAMES; k++)
        if (strcmp(cell, TC_LAB_NAMES[k][0]) == 0) return k;
    return -1;
}

static const char *lab_named(const char *cell, int j) {
    int k = lab_index(cell);
    if (k < 0) return NULL;
    scale_of[j] = TC_LAB_UNITS[k][0];
    offset_of[j] = TC_LAB_UNITS[k][1];
    return TC_LAB_NAMES[k][1];
}

/* The lab's header of contract name `input`, "" where the model's data names it so itself: a
   column the file lacks is said as the lab wrote it (stranger74: `T_Hydraulik`, a name none of
   the lab's files holds, for its `Hydraulik (degC)`). */
static const char *lab_header(const char *input) {
    int k;
    for (k = 0; k < TC_N_LAB_NAMES; k++)
        if (strcmp(input, TC_LAB_NAMES[k][1]) == 0) return TC_LAB_NAMES[k][0];
    return "";
}

/* (names97) The lab's headers a bare header of column j may be, two columns alike but for their
   unit (`T` of `T [degC]` and `T [K]`): -1 where it names one column for sure. The served model
   refuses such a name naming both (naming.bare_names); the stream took its first match. */
static int alike_of[MAX_COLS][2];

/* 1: lab headers k and m are one bare name's two columns: another contract name, or one of
   them read in another unit (its cells converted). */
static int alike(int k, int m) {
    return strcmp(TC_LAB_NAMES[k][1], TC_LAB_NAMES[m][1]) != 0
           || TC_LAB_UNITS[k][0] != 1.0 || TC_LAB_UNITS[k][1] != 0.0
           || TC_LAB_UNITS[m][0] != 1.0 || TC_LAB_UNITS[m][1] != 0.0;
}

/* 1: `cell` (len bytes) is lab header k's text before ` [` (its unit): k's bare form. */
static int bare_of(const char *cell, size_t len, int k) {
    return strncmp(cell, TC_LAB_NAMES[k][0], len) == 0 && TC_LAB_NAMES[k][0][len] == ' '
           && TC_LAB_NAMES[k][0][len + 1] == '[' && strcmp(cell, TC_LAB_NAMES[k][1]) != 0;
}

static const char *named(char *cell, int j) {
    size_t len;
    int k, m;
    const char *lab;
    while (*cell == ' ' || *cell == '"') cell++;
    len = strlen(cell);
    while (len && (cell[len - 1] == ' ' || cell[len - 1] == '"')) cell[--len] = '\0';
    scale_of[j] = 1.0;
    offset_of[j] = 0.0;
    alike_of[j][0] = alike_of[j][1] = -1;
    if ((lab = lab_named(cell, j)) != NULL) return lab;
    /* (streamraw65) a header whose unit is in the unit row under it (`T Halle` over `degC`): the
       reader named it `T Halle [degC]`; the unit row, where there is one, says which (united) */
    /* (restart66) not a contract name itself: the check pack's rows.csv heads `time` in s where
       the lab's header was `time [h]` (read as hours, the pack failed its own check) */
    for (k = 0; len && k < TC_N_LAB_NAMES; k++)
        if (bare_of(cell, len, k)) {
            scale_of[j] = TC_LAB_UNITS[k][0];
            offset_of[j] = TC_LAB_UNITS[k][1];
            for (m = k + 1; m < TC_N_LAB_NAMES; m++)     /* (names97: the first match is not sure) */
                if (bare_of(cell, len, m) && alike(k, m)) alike_of[j][0] = k, alike_of[j][1] = m;
            return TC_LAB_NAMES[k][1];
        }
    return cell;
}

/* 1: `line` is UTF-8 (ASCII included): the check pack's rows.csv, a converted file. A Windows
   logger's `St\344nder` is not (a lead byte 0xE4 wants two continuation bytes). */
static int utf8(const char *line) {
    const unsigned char *p = (const unsigned char *)line;
    while (*p) {
        int more = *p < 0x80 ? 0 : (*p & 0xE0) == 0xC0 && *p >= 0xC2 ? 1 : (*p & 0xF0) == 0xE0
                   ? 2 : (*p & 0xF8) == 0xF0 && *p <= 0xF4 ? 3 : -1;
        if (more < 0) return 0;
        for (p++; more > 0; more--, p++)
            if ((*p & 0xC0) != 0x80) return 0;
    }
    return 1;
}

/* (streamraw65) a line's bytes in data.encoding (TC_ENCODING: cp1252 or latin-1, a Windows
   logger's `T St\344nder [\260C]`) as UTF-8, in place, as the reader decodes the file (a line
   that is UTF-8 already, as the pack's rows.csv are, is left as it is); 0 where
   a byte is none of cp1252's (0x81, 0x8D, 0x8F, 0x90, 0x9D: the reader refuses it too) or the
   line outgrows the buffer. */
static int decoded(char *line, size_t size) {
    static const unsigned short cp1252[32] = {
        0x20AC, 0, 0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160,
        0x2039, 0x0152, 0, 0x017D, 0, 0, 0x2018, 0x2019, 0x201C, 0x201D, 0x2022, 0x2013,
        0x2014, 0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0, 0x017E, 0x0178};
    static char out[MAX_LINE];
    size_t n = 0;
    const unsigned char *p;
    if (TC_ENCODING == 0 || utf8(line)) return 1;   /* (the pack's rows.csv: UTF-8) */
    for (p = (const unsigned char *)line; *p; p++) {
        unsigned code = *p;
        if (code >= 0x80 && code < 0xA0 && TC_ENCODING == 1) {
            code = cp1252[code - 0x80];
            if (!code) return 0;
        }
        if (n + 4 >= size) return 0;
        if (code < 0x80) out[n++] = (char)code;
        else if (code < 0x800) {
            out[n++] = (char)(0xC0 | (code >> 6));
            out[n++] = (char)(0x80 | (code & 0x3F));
        } else {
            out[n++] = (char)(0xE0 | (code >> 12));
            out[n++] = (char)(0x80 | ((code >> 6) & 0x3F));
            out[n++] = (char)(0x80 | (code & 0x3F));
        }
    }
    out[n] = '\0';
    memcpy(line, out, n + 1);
    return 1;
}

/* (deploy71) stdin in UTF-16: 1 little-endian, 2 big-endian (its byte-order mark said so);
   0: bytes, UTF-8 or data.encoding. */
static int utf16_;
static long utf16_at;      /* bytes of a UTF-16 stdin read so far, its mark's two included */

/* A UTF-16 stdin's next two bytes as a code unit (utf16_'s order); -1 at its end, -2 where one
   byte is left (an odd byte count). */
static long utf16_unit(void) {
    int a = getc(stdin), b;
    if (a == EOF) return -1;
    if ((b = getc(stdin)) == EOF) return -2;
    utf16_at += 2;
    return utf16_ == 1 ? (long)(a | b << 8) : (long)(a << 8 | b);
}

/* (deploy71) The next line of a UTF-16 stdin as UTF-8 into `line`, its line end kept.  The
   code takes no library (iconv is POSIX, not on every PLC or NC toolchain), so the transcoding
   is written here: a pair of surrogates is one character.  1, 0 at the end; two bytes that are
   no character (a lone surrogate, an odd byte at the end: said with their line and bytes, as
   the model's reader says them), a NUL (UTF-32 text?) or a line that outgrows the buffer: said,
   exit 2. */
static int utf16_line(char *line, size_t size, long row) {
    size_t n = 0;
    long code, low, at = utf16_at;
    const char *why = NULL;
    while ((code = utf16_unit()) != -1) {
        if (code >= 0xD800 && code < 0xDC00) {       /* a high surrogate: its low one next */
            low = utf16_unit();
            code = low >= 0xDC00 && low <= 0xDFFF ? 0x10000 + ((code - 0xD800) << 10)
                   + (low - 0xDC00) : 0xDC00;
        }
        why = code == -2 ? "an odd byte at the end: UTF-16 writes two a character"
              : code >= 0xDC00 && code < 0xE000 ? "a lone surrogate" : NULL;
        if (why) break;
        if (code == 0 || n + 5 > size) {
            fprintf(stderr, "stream: line %ld: %s\n", row, code ? "longer than the reader's "
                    "buffer" : "a NUL character (UTF-32 text? convert it to UTF-8 first)");
            exit(2);
        }
        if (code < 0x80) {
            line[n++] = (char)code;
        } else if (code < 0x800) {
            line[n++] = (char)(0xC0 | code >> 6);
            line[n++] = (char)(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            line[n++] = (char)(0xE0 | code >> 12);
            line[n++] = (char)(0x80 | (code >> 6 & 0x3F));
            line[n++] = (char)(0x80 | (code & 0x3F));
        } else {
            line[n++] = (char)(0xF0 | code >> 18);
            line[n++] = (char)(0x80 | (code >> 12 & 0x3F));
            line[n++] = (char)(0x80 | (code >> 6 & 0x3F));
            line[n++] = (char)(0x80 | (code & 0x3F));
        }
        if (code == '\n') break;
        at = utf16_at;
    }
    if (why) {
        fprintf(stderr, "stream: line %ld: bytes %ld-%ld are no UTF-16 character (%s; the file "
                "begins with UTF-16's byte-order mark)\n", row, at, code == -2 ? at : at + 1,
                why);
        exit(2);
    }
    line[n] = '\0';
    return n > 0;
}

/* stdin's first bytes: a UTF-16 byte-order mark sets utf16_ (and is dropped); other bytes read
   are put back, or (two of them, the first 0xFF or 0xFE) begin `line`: their count. */
static size_t byte_order(char *line) {
    int a = getc(stdin), b;
    line[0] = '\0';
    if (a != 0xFF && a != 0xFE) {
        if (a != EOF) ungetc(a, stdin);
        return 0;
    }
    if ((b = getc(stdin)) == (a ^ 1)) {       /* FF FE: little-endian, FE FF: big-endian */
        utf16_ = a == 0xFF ? 1 : 2;
        utf16_at = 2;
        return 0;
    }
    line[0] = (char)a;
    line[1] = (char)(b == EOF ? '\0' : b);
    line[2] = '\0';
    return b == EOF ? 1 : 2;
}

/* The next line of stdin (line `row` of the file), decoded (TC_ENCODING; UTF-16 after its
   mark, utf16_line): 1, 0 at its end; a byte data.encoding does not read: said, exit 2. */
static int next_line(char *line, size_t size, long row) {
    static int started;
    size_t n = 0;
    if (!started) started = 1, n = byte_order(line);    /* (the file's first bytes) */
    if (utf16_) return utf16_line(line, size, row);
    if (!(n && line[n - 1] == '\n') && !fgets(line + n, (int)(size - n), stdin) && !n) return 0;
    if (!decoded(line, size)) {
        fprintf(stderr, "stream: line %ld: a byte %s does not read (data.encoding of the model's "
                "data), or the line is too long\n", row,
                TC_ENCODING == 1 ? "cp1252" : "latin-1");
        exit(2);
    }
    return 1;
}

/* 1: `cell` (spaces and quotes round it dropped) is one of data.missing_values' text marks. */
static int is_mark(const char *cell) {
    size_t len;
    int k;
    while (*cell == ' ' || *cell == '"') cell++;
    len = strlen(cell);
    while (len && (cell[len - 1] == ' ' || cell[len - 1] == '"' || cell[len - 1] == '\r'
                   || cell[len - 1] == '\n')) len--;
    for (k = 0; k < TC_N_MISSING; k++)
        if (TC_MISSING[k][0] && strlen(TC_MISSING[k]) == len && strncmp(cell, TC_MISSING[k], len) == 0)
            return 1;
    return 0;
}

/* 1: `v` (a cell's number) is one of data.missing_values' numbers, however the cell wrote it
   (lab74: AmeriFlux's -9999 as -9999.000). */
static int is_number_mark(double v) {
    int k;
    for (k = 0; k < TC_N_MISSING_VALUES; k++)
        if (v == TC_MISSING_VALUE[k]) return 1;
    return 0;
}

/* 1: `line` is blank or a `#` comment (a DAQ script's block above its header). */
static int comment_or_blank(const char *line) {
    const char *p = line + strspn(line, " \t\r\n");
    return *p == '\0' || *p == '#';
}

/* A header cell written as a comment (`# t [s]`: a DAQ script's, numpy's savetxt) without its
   `#` and the blanks after it (stranger66). */
static char *uncommented(char *cell) {
    cell += strspn(cell, "#");
    return cell + strspn(cell, " \t");
}

/* The separator a header line says: ';', a tab or '|' where it holds one, else ','. */
static char separator_of(const char *line) {
    return strchr(line, ';') ? ';' : strchr(line, '\t') ? '\t' : strchr(line, '|') ? '|' : ',';
}

/* 1: a header's cell is the status word (data.bits) one of whose bits is input i (lead91). */
static int word_holds(const char *cell, int i) {
    int k;
    for (k = 0; k < TC_N_WORD_BITS; k++)
        if (strcmp(TC_INPUT_NAMES[i], TC_WORD_BITS[k][0]) == 0
            && strcmp(cell, TC_WORD_BITS[k][1]) == 0) return 1;
    return 0;
}

/* The first input of TC_INPUT_NAMES the line inputs_named_over last looked at does not name
   (-1: it names every one), and that line's cell in the header's column of it (audit105). */
static int unnamed_input = -1;

/* How many inputs of TC_INPUT_NAMES `line` (not changed) names, with the unit row `units` under
   it where `units` is one (NULL: none; unit_named) (sets `sep` to the line's, and
   unnamed_input). */
static int inputs_named_over(const char *line, const char *units) {
    static char text[MAX_LINE];
    char *cells[MAX_COLS];
    const char *names[MAX_COLS];
    int ncols, i, j, found, n = 0;
    strcpy(text, line);
    sep = separator_of(text);
    ncols = split(text, cells);
    if (ncols > 0 && cells[0][0] == '#')     /* (a header written as a comment: stranger66) */
        cells[0] = uncommented(cells[0]);
    for (j = 0; j < ncols; j++) names[j] = named(twin(cells, j), j);
    if (units != NULL) unit_named(cells, ncols, units, names);
    unnamed_input = -1;
    for (i = 0; i < TC_N_INPUTS; i++) {
        for (found = 0, j = 0; j < ncols && !found; j++)
            found = strcmp(names[j], TC_INPUT_NAMES[i]) == 0 || word_holds(cells[j], i);
        if (!found && unnamed_input < 0) unnamed_input = i;
        n += found;
    }
    return n;
}

static int inputs_named(const char *line) { return inputs_named_over(line, NULL); }

/* `line` names every input, as the header must: a logger's preamble line above it does not. */
static int names_every_input(const char *line) {
    return inputs_named(line) == TC_N_INPUTS;
}

/* `text` without the thousands separator `mark` where it groups digits by three (data.thousands:
   1.234,5 or 1,234.5, as the reader reads them; a date's 07.06.2027 is left as it is). */
static void ungroup(char *text, char mark) {
    char *p, *w;
    for (p = text; (p = strchr(p, mark)) != NULL; p++) {
        if (p == text || p[-1] < '0' || p[-1] > '9') return;
        if (!(p[1] >= '0' && p[1] <= '9' && p[2] >= '0' && p[2] <= '9' && p[3] >= '0'
              && p[3] <= '9') || (p[4] >= '0' && p[4] <= '9')) return;
    }
    for (p = w = text; *p; p++)
        if (*p != mark) *w++ = *p;
    *w = '\0';
}

/* A cell's number; NAN when empty, and when it is no number as a whole (then `bad` is set). */
static double value(const char *cell, int *bad) {
    char text[MAX_CELL], *end, *c;
    double v;
    while (*cell == ' ' || *cell == '"') cell++;
    if (*cell == '\0' || is_mark(cell)) return NAN;   /* (a data.missing_values mark: empty) */
    strncpy(text, cell, MAX_CELL - 1);
    text[MAX_CELL - 1] = '\0';
    if (TC_THOUSANDS[0]) ungroup(text, TC_THOUSANDS[0]);
    if (sep != ',' && (c = strchr(text, ',')) != NULL) *c = '.';   /* a decimal comma */
    v = strtod(text, &end);
    while (*end == ' ' || *end == '"') end++;
    if (end == text || *end != '\0') { *bad = 1; return NAN; }
    /* (lab75: an infinite reading, a logger's INF for an overflow or an open input: missing) */
    return is_number_mark(v) || isinf(v) ? NAN : v;
}

/* 1: `cell` (spaces and quotes round it dropped) reads as a number with a decimal comma, `22,61`
   (the reader's hint: tables._bad_cell_error), in a stream whose separator is ','. */
static int decimal_comma(const char *cell) {
    const char *p;
    while (*cell == ' ' || *cell == '"') cell++;
    if (sep != ',' || *cell == '\0') return 0;
    p = cell + (*cell == '+' || *cell == '-');
    p += strspn(p, "0123456789");
    if (*p++ != ',' || *p < '0' || *p > '9') return 0;
    p += strspn(p, "0123456789");
    while (*p == ' ' || *p == '"') p++;
    return *p == '\0';
}

/* 1: `cell` is a channel property's label ('T0', 'dt', 'Delta t'): a letter, then letters,
   digits, '_' or '.', one space at most. */
static int is_label(const char *cell) {
    int spaces = 0;
    while (*cell == ' ' || *cell == '"') cell++;
    if (!((*cell >= 'A' && *cell <= 'Z') || (*cell >= 'a' && *cell <= 'z'))) return 0;
    for (; *cell && *cell != '"' && *cell != '\r' && *cell != '\n'; cell++) {
        if (*cell == ' ' && cell[1] && cell[1] != ' ' && cell[1] != '\r' && cell[1] != '\n') {
            if (++spaces > 1) return 0;
        } else if (*cell == ' ') {
            break;
        } else if (!((*cell >= 'A' && *cell <= 'Z') || (*cell >= 'a' && *cell <= 'z')
                     || (*cell >= '0' && *cell <= '9') || *cell == '_' || *cell == '.')) {
            return 0;
        }
    }
    return 1;
}

/* `line` without its line end (in place). */
static const char *strip_end(char *line) {
    line[strcspn(line, "\r\n")] = '\0';
    return line;
}

/* (audit96) `line` (without its line end) added to `above`, the preamble's lines each ended by
   '\n', where it fits */
static void kept(char *above, const char *line) {
    size_t n = strlen(above), len = strcspn(line, "\r\n");
    if (len == 0 || n + len + 2 > MAX_LINE) return;
    memcpy(above + n, line, len);
    above[n + len] = '\n';
    above[n + len + 1] = '\0';
}

/* (audit96) `line` (its end stripped) is one of the preamble's lines `above` */
static int among(const char *above, const char *line) {
    size_t len = strlen(line);
    const char *at = above;
    while (len > 0 && (at = strstr(at, line)) != NULL) {
        if ((at == above || at[-1] == '\n') && at[len] == '\n') return 1;
        at++;
    }
    return 0;
}

/* `cell` without the spaces and double quotes around it (in place). */
static const char *trimmed(char *cell) {
    size_t len;
    while (*cell == ' ' || *cell == '"') cell++;
    len = strlen(cell);
    while (len && (cell[len - 1] == ' ' || cell[len - 1] == '"')) cell[--len] = '\0';
    return cell;
}

/* (audit86) A header written twice, as the reader reads it (twins.py): its k-th occurrence
   `<name>#<k>` before its unit (`Halle#2 [degC]`), which the model's data names where it read
   that column (a copy of the first it left out: no input then); the second was refused. */
#define MAX_NAME 256
static char *numbered(char **raw, int j, char *out) {
    const char *cell = trimmed(raw[j]), *unit;
    size_t len = strlen(cell), at = len;
    int i, k = 1;
    for (i = 0; i < j; i++) k += strcmp(trimmed(raw[i]), cell) == 0;
    if (k == 1 || len + 12 > MAX_NAME) return raw[j];
    unit = len ? strrchr(cell, cell[len - 1] == ']' ? '[' : '(') : NULL;
    if (unit && unit > cell && unit[-1] == ' ' && (cell[len - 1] == ']' || cell[len - 1] == ')'))
        at = (size_t)(unit - 1 - cell);
    snprintf(out, MAX_NAME, "%.*s#%d%s", (int)at, cell, k, cell + at);
    return out;
}

static char twins[MAX_COLS][MAX_NAME];
static char *twin(char **raw, int j) { return numbered(raw, j, twins[j]); }

/* (streamraw65, names97b) `line` is a unit row under the header `raw` (`;;degC;W;-;um`: every
   cell it fills no number, a unit under an input among them): 1, each column's name in `names`
   (the header's, `named`) as the reader names it, the header joined to its unit (`T Halle
   [degC]`), then a name still written twice numbered (`Temp;Temp` over `degC;degC`: `Temp
   [degC]`, `Temp#2 [degC]`; `T;T` over `degC;K`: `T [degC]`, `T [K]`, which the bare header's
   twin `T#2` never named): layout.with_units, then twins.occurrences.  A joined name the
   model's data does not hold keeps the header's name.  0, `names` as they were: no unit row. */
static int unit_named(char **raw, int ncols, const char *line, const char **names) {
    static char copy[MAX_LINE], texts[MAX_COLS][MAX_NAME], joined[MAX_COLS][MAX_NAME];
    char *units[MAX_COLS], *text[MAX_COLS];
    int lab[MAX_COLS], n, j, k, filled = 0;
    strcpy(copy, line);
    n = split(copy, units);
    for (j = 0; j < n; j++) {
        int bad = 0;
        units[j] = (char *)trimmed(units[j]);
        if (*units[j] && (is_mark(units[j]) || isfinite(value(units[j], &bad)) || !bad)) return 0;
    }
    for (j = 0; j < ncols; j++) {
        const char *u = j < n ? units[j] : "";
        if (!*u || snprintf(texts[j], MAX_NAME, "%s [%s]", trimmed(raw[j]), u) >= MAX_NAME)
            snprintf(texts[j], MAX_NAME, "%s", trimmed(raw[j]));
        text[j] = texts[j];
    }
    for (j = 0; j < ncols; j++) {
        lab[j] = j < n && *units[j] ? lab_index(numbered(text, j, joined[j])) : -1;
        for (k = 0; j < n && *units[j] && k < TC_N_INPUTS; k++)   /* (a unit under an input) */
            if (strcmp(names[j], TC_INPUT_NAMES[k]) == 0
                || (lab[j] >= 0 && strcmp(TC_LAB_NAMES[lab[j]][1], TC_INPUT_NAMES[k]) == 0))
                filled = 1;
    }
    for (j = 0; filled && j < ncols; j++)
        if (lab[j] >= 0)                                   /* (its unit row says which) */
            names[j] = lab_named(TC_LAB_NAMES[lab[j]][0], j), alike_of[j][0] = -1;
    return filled;
}

/* Column j's cell in the contract's unit (NAN stays NAN). */
static double converted(char **cells, int j, int *bad) {
    double v = value(cells[j], bad);
    v = v * scale_of[j];       /* (two statements: the reader multiplies, then adds) */
    return v + offset_of[j];
}

/* Wall-clock times are parsed here by hand: standard C has no parser of dates (strptime and
   timegm are POSIX or GNU, not on every PLC or NC toolchain) and the code takes no library.
   Reads `least` to `most` digits at *p, no more, into *v. */
static int digits(const char **p, int least, int most, long *v) {
    int n = 0;
    *v = 0;
    while (n < most && **p >= '0' && **p <= '9') { *v = *v * 10 + (*(*p)++ - '0'); n++; }
    return n >= least && !(**p >= '0' && **p <= '9');
}

/* Days from 1970-01-01 to a date of the Gregorian calendar (H. Hinnant's days_from_civil). */
static long long days_from_civil(long y, long m, long d) {
    long era, yoe, doy;
    y -= m <= 2;
    era = (y >= 0 ? y : y - 399) / 400;
    yoe = y - era * 400;
    doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    return (long long)era * 146097 + yoe * 365 + yoe / 4 - yoe / 100 + doy - 719468;
}

/* A wall-clock time as whole seconds since 1970 (a zone offset taken off: UTC) and a fraction
   (s): ISO 8601 `2023-01-07T08:45:00` (a space for the T, seconds optional, a fraction after
   '.' or ',', then `Z`, `+01:00`, `+0100` or `+01`) or day-first `07.01.2023 08:45:00` (or
   `07.01.23 08:45`, a two-digit year: 69-99 the 1900s, as strptime's %y reads it), or with
   TC_SLASHED a date with slashes in data.time's order (1 day first, 2 month first: a Keysight
   DAQ's `03/01/2027 06:00:00:011`, its milliseconds after a colon).
   Returns LOCAL_TIME without an offset, ZONED_TIME with one, 0 for anything else (a date or a
   time of day alone, an impossible date).  Without an offset it is the logger's own clock, as
   the served model reads it (no daylight saving time). */
static int wall_clock(const char *cell, long long *whole, double *fraction) {
    static const int month_days[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const char *p = cell;
    long y, mo, d, h, mi, s = 0, ns = 0, oh = 0, om = 0, offset = 0, scale = 1000000000L;
    int kind = LOCAL_TIME, iso;
    while (*p == ' ' || *p == '"') p++;
    cell = p;
    iso = digits(&p, 4, 4, &y) && *p == '-';
    if (iso) {
        p++;
        if (!digits(&p, 2, 2, &mo) || *p++ != '-' || !digits(&p, 2, 2, &d)) return 0;
    } else {
        p = cell;
        const char *year;
        char mark;
        if (!digits(&p, 1, 2, &d)) return 0;
        mark = *p++;
        if (!(mark == '.' || (TC_SLASHED && mark == '/')) || !digits(&p, 1, 2, &mo)
            || *p++ != mark)
            return 0;
        if (mark == '/' && TC_SLASHED == 2) { long first = d; d = mo; mo = first; }
        year = p;
        if (!digits(&p, 2, 4, &y) || p - year == 3) return 0;
        if (p - year == 2) y += y < 69 ? 2000 : 1900;   /* Excel's 07.01.23: strptime's %y */
    }
    if (*p != 'T' && *p != ' ') return 0;
    p++;
    if (!digits(&p, 1, 2, &h) || *p++ != ':' || !digits(&p, 2, 2, &mi)) return 0;
    if (*p == ':') {
        p++;
        if (!digits(&p, 2, 2, &s)) return 0;
        /* to the nanosecond, as the served model reads it (a Keysight DAQ's after a colon) */
        if (*p == '.' || *p == ',' || (TC_SLASHED && *p == ':')) {
            p++;
            if (!(*p >= '0' && *p <= '9')) return 0;
            for (; *p >= '0' && *p <= '9'; p++)
                if (scale > 1) { scale /= 10; ns += (*p - '0') * scale; }
        }
    }
    if (iso && (*p == 'Z' || *p == '+' || *p == '-')) {
        kind = ZONED_TIME;
        if (*p == 'Z') p++;
        else {
            int sign = *p++ == '-' ? -1 : 1;
            if (!digits(&p, 2, 2, &oh)) return 0;
            if (*p == ':') p++;
            if (*p >= '0' && *p <= '9' && !digits(&p, 2, 2, &om)) return 0;
            if (oh > 23 || om > 59) return 0;
            offset = sign * (oh * 3600 + om * 60);
        }
    }
    while (*p == ' ' || *p == '"') p++;
    if (*p != '\0' || mo < 1 || mo > 12 || d < 1 || d > month_days[mo - 1] || h > 23 || mi > 59
        || s > 59 || (mo == 2 && d == 29 && (y % 4 != 0 || (y % 100 == 0 && y % 400 != 0))))
        return 0;
    *whole = days_from_civil(y, mo, d) * 86400 + h * 3600 + mi * 60 + s - offset;
    *fraction = ns / 1e9;
    return kind;
}

/* (realexport73) A date and time written as 12 or 14 digits alone, `yyyymmddHHMM[SS]` (the
   AmeriFlux TIMESTAMP_START of a Campbell Scientific logger's flux table, 202503272330), as
   whole seconds since 1970 into *whole, as the model's reader reads it: 1 where the cell is
   one (a year 1900-2199, a date of the calendar), else 0 (a number of seconds). */
static int compact_clock(const char *cell, long long *whole) {
    static const int month_days[12] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    const char *p = cell, *start;
    long y, mo, d, h, mi, s = 0;
    while (*p == ' ' || *p == '"') p++;
    start = p;
    while (*p >= '0' && *p <= '9') p++;
    if (p - start != 12 && p - start != 14) return 0;
    p = start;
    y = (p[0] - '0') * 1000 + (p[1] - '0') * 100 + (p[2] - '0') * 10 + (p[3] - '0');
    if (y < 1900 || y > 2199) return 0;
    p = start + 4;
    mo = (p[0] - '0') * 10 + (p[1] - '0');
    d = (p[2] - '0') * 10 + (p[3] - '0');
    h = (p[4] - '0') * 10 + (p[5] - '0');
    mi = (p[6] - '0') * 10 + (p[7] - '0');
    if (p[8] >= '0' && p[8] <= '9') s = (p[8] - '0') * 10 + (p[9] - '0');
    p = start + (p[8] >= '0' && p[8] <= '9' ? 14 : 12);
    while (*p == ' ' || *p == '"') p++;
    if (*p != '\0' || mo < 1 || mo > 12 || d < 1 || d > month_days[mo - 1] || h > 23 || mi > 59
        || s > 59 || (mo == 2 && d == 29 && (y % 4 != 0 || (y % 100 == 0 && y % 400 != 0))))
        return 0;
    *whole = days_from_civil(y, mo, d) * 86400 + h * 3600 + mi * 60 + s;
    return 1;
}

/* (iso67) A logger's time since its start, `h:mm:ss` (data.time=elapsed, TC_ELAPSED): hours
   past 24 as they are (`59:59:00.0`), a fraction of a second after '.' or ',', as seconds into
   *t; 0 for anything else. */
static int elapsed(const char *cell, double *t) {
    const char *p = cell;
    long h, mi, s;
    double fraction = 0.0, scale = 0.1;
    while (*p == ' ' || *p == '"') p++;
    if (!digits(&p, 1, 9, &h) || *p++ != ':' || !digits(&p, 2, 2, &mi) || *p++ != ':'
        || !digits(&p, 2, 2, &s) || mi > 59 || s > 59) return 0;
    if (*p == '.' || *p == ',') {
        p++;
        if (!(*p >= '0' && *p <= '9')) return 0;
        for (; *p >= '0' && *p <= '9'; p++, scale /= 10) fraction += (*p - '0') * scale;
    }
    while (*p == ' ' || *p == '"') p++;
    if (*p != '\0') return 0;
    *t = h * 3600.0 + mi * 60.0 + s + fraction;
    return 1;
}

/* The stream's clock: the form of its first time, and the first time of the campaign. */
static struct { int kind, started; long long origin; double origin_fraction; } clock_;

/* (lead91) TC_DAY_SECONDS: the time a logger's seconds since midnight (`Seconds of day`,
   data89b), read as the reader's past_midnight reads it: a day added at each step back by more
   than half a day (the clock passing midnight), so a pause across midnight is the pause it is
   (runs_at_pauses: TC_PAUSE_S) and no step back; a step forward of half a day or more reads as
   well a step back and is refused, as the reader refuses it.  A time past a day is taken as it
   is: the rows `thermocomp rows` and the check pack write carry the days already. */
static double day_last = NAN, day_added = 0.0;
static int day_passed;         /* (dep107b) the last row's clock passed midnight: it went back */

static int of_day(double *t, long row) {
    double raw = *t;
    day_passed = 0;
    if (!isfinite(raw)) return 0;
    *t = raw + day_added;
    while (isfinite(day_last) && *t < day_last - 43200.0)
        day_added += 86400.0, *t += 86400.0, day_passed = 1;
    if (isfinite(day_last) && *t - day_last >= 43200.0) {
        fprintf(stderr, "stream: line %ld: the time of day (%.10g s, seconds since midnight) "
                "steps %.3g h forward: as well %.3g h back, a day passed (no date to tell; "
                "the reader refuses it alike): give the date column with it, or cut the "
                "record there\n", row, raw, (*t - day_last) / 3600.0,
                (86400.0 - (*t - day_last)) / 3600.0);
        return 2;
    }
    day_last = *t;
    return 0;
}

/* A row's time cell as seconds (NAN: none) into *t; wall-clock times as seconds since the
   campaign's first.  Returns 0, or 2 after saying why the cell is refused. */
static int time_of(const char *cell, long row, double scale, double offset, double *t) {
    static const char *const forms[] = {"", "seconds", "a date and time without a zone offset",
                                        "a date and time with a zone offset"};
    long long whole = 0;
    double fraction = 0.0;
    int bad = 0, kind;
    *t = value(cell, &bad);
    if ((TC_ELAPSED || TC_DAY_SECONDS) && bad) {
        /* (iso67) data.time=elapsed: h:mm:ss since the start; (lead91) of_day: the time of day
           as h:mm:ss, its seconds since midnight (of_day() carries the days) */
        if (!elapsed(cell, t)) {
            fprintf(stderr, "stream: row %ld: the time is no h:mm:ss %s\n", row, TC_ELAPSED
                    ? "since the start (data.time=elapsed: 0:00:00, 25:30:00.5)"
                    : "of the day (data.time=of_day: 23:59:30, 0:00:30)");
            return 2;
        }
        clock_.kind = SECONDS;
        return 0;
    }
    kind = isfinite(*t) ? (compact_clock(cell, &whole) ? LOCAL_TIME : SECONDS)
         : bad ? wall_clock(cell, &whole, &fraction) : 0;
    if (bad && !kind) {
        fprintf(stderr, "stream: line %ld: the time is no number of seconds nor a date and time "
                "(2023-01-07T08:45:00, 07.01.2023 08:45:00; a time of day alone goes back at "
                "midnight)\n", row);
        return 2;
    }
    if (kind && clock_.kind && kind != clock_.kind) {
        fprintf(stderr, "stream: line %ld: the time is %s, the stream's first %s\n", row,
                forms[kind], forms[clock_.kind]);
        return 2;
    }
    if (kind) clock_.kind = kind;
    if (kind == SECONDS) {                /* a time in min, h, ms: in s, as the reader reads it */
        *t = *t * scale;
        *t = *t + offset;
    }
    if (kind > SECONDS) {
        if (!clock_.started) {
            clock_.origin = whole;
            clock_.origin_fraction = fraction;
            clock_.started = 1;
        }
        *t = (double)(whole - clock_.origin) + (fraction - clock_.origin_fraction);
    }
    return 0;
}

/* A row's time into *t (time_of): the date and its time of day joined (`stamp`, clock_col) or
   the time column's cell, a time of day carried past midnight (TC_DAY_SECONDS: of_day); *t as it
   was without a time column.  Returns 0, or 2 after saying why. */
static int row_time(char **cells, int time_col, int clock_col, const char *stamp, long row,
                    double *t) {
    if (time_col < 0) return 0;
    if (clock_col >= 0) return time_of(stamp, row, 1.0, 0.0, t);
    if (time_of(cells[time_col], row, scale_of[time_col], offset_of[time_col], t) != 0) return 2;
    return TC_DAY_SECONDS ? of_day(t, row) : 0;
}

/* --state FILE: what a restarted process needs to go on as if it had not stopped. The bytes
   are this build's (the sizes and a mark are checked), as tc_state is plain data; (dep107b) and
   a blank line read last, not yet decided (the next row's time decides it: a stream cut there
   went on from a reset where the uninterrupted one reads a stray blank line as nothing), and a
   time of day's last time and the days added (the days came back from the last time read,
   but as a step back past midnight: a blank line pending then started a campaign, 4.55 um off
   on a lag bank).  A state of the mark before (tcstat1) is refused as another build's. */
static const char STATE_MARK[8] = "tcstat2";
static int state_blank;        /* the blank line pending, as saved and restored */

/* 1: FILE read back into *s and the stream's clock and run; 0: no FILE (a cold start); -1: FILE
   is no state of this build (another model, compiler or machine; truncated). */
static int restore_state(const char *path, tc_state *s, char *run) {
    char mark[sizeof STATE_MARK];
    unsigned long sizes[3];
    int ok;
    FILE *f = fopen(path, "rb");
    if (f == NULL) return 0;
    ok = fread(mark, sizeof mark, 1, f) == 1 && memcmp(mark, STATE_MARK, sizeof mark) == 0
         && fread(sizes, sizeof sizes, 1, f) == 1 && sizes[0] == sizeof *s
         && sizes[1] == sizeof clock_ && sizes[2] == MAX_CELL
         && fread(s, sizeof *s, 1, f) == 1 && fread(&clock_, sizeof clock_, 1, f) == 1
         && fread(run, MAX_CELL, 1, f) == 1 && fread(&state_blank, sizeof state_blank, 1, f) == 1
         && fread(&day_last, sizeof day_last, 1, f) == 1 && fread(&day_added, sizeof day_added, 1, f) == 1
         && fgetc(f) == EOF;
    fclose(f);
    return ok ? 1 : -1;
}

/* Writes the state to FILE.tmp (`tmp`), then renames it over FILE; 0 where it cannot. Where
   rename does not replace a file (Windows), FILE is removed first: a stop in between leaves
   FILE.tmp, the state, to be renamed by hand. */
static int save_state(const char *path, char *tmp, const tc_state *s, const char *run) {
    unsigned long sizes[3] = {sizeof *s, sizeof clock_, MAX_CELL};
    int ok;
    FILE *f = fopen(tmp, "wb");
    if (f == NULL) return 0;
    ok = fwrite(STATE_MARK, sizeof STATE_MARK, 1, f) == 1 && fwrite(sizes, sizeof sizes, 1, f) == 1
         && fwrite(s, sizeof *s, 1, f) == 1 && fwrite(&clock_, sizeof clock_, 1, f) == 1
         && fwrite(run, MAX_CELL, 1, f) == 1 && fwrite(&state_blank, sizeof state_blank, 1, f) == 1
         && fwrite(&day_last, sizeof day_last, 1, f) == 1 && fwrite(&day_added, sizeof day_added, 1, f) == 1;
    ok = fclose(f) == 0 && ok;
    if (ok && rename(tmp, path) != 0) ok = remove(path) == 0 && rename(tmp, path) == 0;
    return ok;
}

/* After a row: the state saved where --state names a file (1), or said that it cannot be (0). */
static int saved(const char *path, char *tmp, const tc_state *s, const char *run) {
    if (path == NULL || save_state(path, tmp, s, run)) return 1;
    fprintf(stderr, "stream: cannot write the state file %s\n", path);
    return 0;
}

/* --check FILE: the expected corrections (a header naming TC_OUTPUT_NAMES in order, then one
   row of numbers per row of corrections, ',' and '.'), the tolerance and the largest difference
   seen (|c - expected|, its output and input line). */
static struct {
    FILE *f;
    const char *path;
    double um, relative, worst;
    long rows, worst_line, line;
    int worst_output;
} check_ = {NULL, NULL, CHECK_UM, CHECK_RELATIVE, 0.0, 0, 0, 1, 0};

/* PATH opened into *f and its first line split into cells (text holds them): their number;
   -1 after saying why not.  (The expected corrections' and flags' files alike.) */
static int open_headed(const char *path, FILE **f, char *text, int size, char **cells) {
    *f = fopen(path, "r");
    if (*f == NULL) {
        fprintf(stderr, "stream: cannot read %s\n", path);
        return -1;
    }
    return fgets(text, size, *f) ? split_by(text, cells, ',') : 0;
}

/* 1: FILE opened and its header names this build's outputs; 0 after saying why not. */
static int check_open(void) {
    static char text[MAX_LINE];
    char *cells[MAX_COLS];
    int n, i;
    if ((n = open_headed(check_.path, &check_.f, text, sizeof text, cells)) < 0) return 0;
    for (i = 0; n == TC_N_OUTPUTS && i < n; i++)
        if (strcmp(cells[i], TC_OUTPUT_NAMES[i]) != 0) break;
    if (n != TC_N_OUTPUTS || i < n) {
        fprintf(stderr, "stream: %s does not name this build's outputs (", check_.path);
        for (i = 0; i < TC_N_OUTPUTS; i++) fprintf(stderr, "%s%s", i ? "," : "", TC_OUTPUT_NAMES[i]);
        fprintf(stderr, ") on its first line: another model's pack?\n");
        return 0;
    }
    return 1;
}

/* The corrections c of input line `row` against FILE's next row: 0 within the tolerance, 1 (not)
   or 2 (FILE unreadable there) after saying where. */
/* (cmon76) the sensor monitor's events on stderr: each exclusion and re-admission, a common
   step re-referenced (cmon80), and where a rule of the served monitor that is not in the code
   sets in (from there the code may part from the served model); 100 lines at most.  (cmon92b)
   Where that rule sets in at a sample whose first event is another (an exclusion), both are
   said: every rule the code does not follow is named. */
static void said_event(long row, int sensor, int rule) {
    static int said = 0;
    if (said++ < 100)
        fprintf(stderr, "stream: line %ld: monitor: %s: %s%s\n", row,
                TC_INPUT_NAMES[TC_MONITORED[sensor]], TC_MONITOR_REASONS[rule],
                said == 100 ? " (no more said)" : "");
}

static void said_monitor(const tc_state *s, long row) {
    static int flagged = 0;
    int now = (s->mon_flags & TC_MON_NOT_IN_CODE) != 0, sets_in = now && !flagged;
    if (s->mon_rule && (s->mon_flags & (TC_MON_EXCLUDED | TC_MON_READMITTED | TC_MON_REREFERENCED)
                        || sets_in))
        said_event(row, s->mon_sensor, s->mon_rule);
    if (sets_in && s->mon_missed && s->mon_missed != s->mon_rule)
        said_event(row, s->mon_missed_sensor, s->mon_missed);
    flagged = now;
}

/* (cflags100) --flags: the monitor's state after a row's corrections, as numbers and names a
   control's integrator splits at ',' (0/1 per kind; no quoting needed); NULL: the header's names.
   Without TC_MONITOR the state's monitor fields are never set: 0 and none out. */
static int flag_on(const tc_state *s, int k) {
    return TC_MONITOR && (s->mon_flags & TC_FLAG_BITS[k]) != 0;
}

/* The monitored sensors out, in the order they went out, ';' between them ("" none). */
static const char *out_names(const tc_state *s) {
    static char text[MAX_LINE];
    int k;
    text[0] = '\0';
    for (k = 0; TC_MONITOR && k < s->mon_nout; k++) {
        if (k) strcat(text, ";");
        strncat(text, TC_INPUT_NAMES[TC_MONITORED[s->mon_out_set[k]]],
                sizeof text - strlen(text) - 2);
    }
    return text;
}

/* (cin103) what a row's time was taken as, `time_read` after the monitor's columns */
enum { TIME_AS_GIVEN, TIME_NONE, TIME_NOT_AFTER, TIME_REPEATED };

static void printed_flags(const tc_state *s, int time_read) {
    int k;
    for (k = 0; k < TC_N_FLAG_KINDS; k++)
        if (s == NULL) printf(",%s", TC_FLAG_NAMES[k]);
        else printf(",%d", flag_on(s, k));
    printf(",%s", s == NULL ? "excluded_inputs" : out_names(s));
    if (s == NULL) printf(",time_read");
    else printf(",%d", time_read);
}

/* (cin103) The row of TC_TWIN_REFUSED holding `header` (-1: none): a copy of it whose values
   are apart from the first's is refused, as the model's reader refuses the file. */
static int twin_refused(const char *header) {
    int k;
    for (k = 0; k < TC_N_TWINS_REFUSED; k++)
        if (strcmp(header, TC_TWIN_REFUSED[k]) == 0) return k;
    return -1;
}

/* The input ended at line `row`: 1 (said) where a --check file still holds a row after its
   line `line`, else 0. */
static int holds_more(FILE *f, const char *path, long line, long row) {
    static char text[MAX_LINE];
    while (fgets(text, sizeof text, f))
        if (text[strspn(text, " \t\r\n")] != '\0') {
            fprintf(stderr, "stream: check: the input ended at line %ld, %s holds more rows "
                    "(from its line %ld)\n", row, path, line + 1);
            return 1;
        }
    return 0;
}

/* (packflags100) --check-flags FILE: the monitor's flags the mirror expects per row (a pack's
   check/<campaign>/flags.csv: a header naming TC_FLAG_NAMES and excluded_inputs, then per row
   0/1 per kind and the sensors out, ';' between them), compared as --flags prints them. */
static struct {
    FILE *f;
    const char *path;
    long rows, line;
} flags_ = {NULL, NULL, 0, 1};

/* 1: FILE opened and its header names the flag columns; 0 after saying why not. */
static int flags_open(void) {
    static char text[MAX_LINE];
    char *cells[MAX_COLS];
    int n, k;
    if ((n = open_headed(flags_.path, &flags_.f, text, sizeof text, cells)) < 0) return 0;
    for (k = 0; n == TC_N_FLAG_KINDS + 1 && k < TC_N_FLAG_KINDS; k++)
        if (strcmp(cells[k], TC_FLAG_NAMES[k]) != 0) break;
    if (n != TC_N_FLAG_KINDS + 1 || k < TC_N_FLAG_KINDS || strcmp(cells[k], "excluded_inputs")) {
        fprintf(stderr, "stream: %s does not name this build's flags (", flags_.path);
        for (k = 0; k < TC_N_FLAG_KINDS; k++) fprintf(stderr, "%s,", TC_FLAG_NAMES[k]);
        fprintf(stderr, "excluded_inputs) on its first line\n");
        return 0;
    }
    return 1;
}

/* The monitor's state s after input line `row` against FILE's next row: 0 as expected, 1 (a
   flag or the sensors out differ: the row, the flag and both values named) or 2 (FILE
   unreadable there). */
static int flags_row(long row, const tc_state *s) {
    static char text[MAX_LINE];
    char *cells[MAX_COLS];
    int k, bad = 0;
    double want;
    flags_.line++;
    if (!fgets(text, sizeof text, flags_.f)) {
        fprintf(stderr, "stream: check: %s ends at line %ld, before the flags of input line "
                "%ld\n", flags_.path, flags_.line - 1, row);
        return 1;
    }
    if (split_by(text, cells, ',') != TC_N_FLAG_KINDS + 1) {
        fprintf(stderr, "stream: check: %s line %ld has not %d cells\n", flags_.path,
                flags_.line, TC_N_FLAG_KINDS + 1);
        return 2;
    }
    for (k = 0; k < TC_N_FLAG_KINDS; k++) {
        want = value(cells[k], &bad);
        if (bad || (want != 0.0 && want != 1.0)) {
            fprintf(stderr, "stream: check: %s line %ld: %s is not 0 or 1\n", flags_.path,
                    flags_.line, TC_FLAG_NAMES[k]);
            return 2;
        }
        if (flag_on(s, k) != (int)want) {
            fprintf(stderr, "stream: flag check failed at input line %ld (row %ld of the stream): "
                    "%s = %d, expected %d (%s line %ld)\n", row, flags_.rows + 1,
                    TC_FLAG_NAMES[k], flag_on(s, k), (int)want, flags_.path, flags_.line);
            return 1;
        }
    }
    if (strcmp(out_names(s), cells[k]) != 0) {
        fprintf(stderr, "stream: flag check failed at input line %ld (row %ld of the stream): "
                "excluded_inputs = '%s', expected '%s' (%s line %ld)\n", row, flags_.rows + 1,
                out_names(s), cells[k], flags_.path, flags_.line);
        return 1;
    }
    flags_.rows++;
    return 0;
}

/* The input ended: 0 when FILE ended too (said), else 1. */
static int flags_end(long row) {
    if (holds_more(flags_.f, flags_.path, flags_.line, row)) return 1;
    fprintf(stderr, "stream: flag check passed: %ld rows' monitor flags as %s\n", flags_.rows,
            flags_.path);
    return 0;
}

/* (cdrop77) 1: input i is one the sensor monitor judges, its missing reading tc_step's */
static int monitored(int i) {
    int k;
    for (k = 0; k < TC_N_MONITORED; k++)
        if (TC_MONITORED[k] == i) return 1;
    return 0;
}

static int check_row(long row, const double *c) {
    static char text[MAX_LINE];
    char *cells[MAX_COLS];
    double want, diff;
    int i, bad = 0;
    check_.line++;
    if (!fgets(text, sizeof text, check_.f)) {
        fprintf(stderr, "stream: check: %s ends at line %ld, before the corrections of input "
                "line %ld\n", check_.path, check_.line - 1, row);
        return 1;
    }
    if (split_by(text, cells, ',') != TC_N_OUTPUTS) {
        fprintf(stderr, "stream: check: %s line %ld has not %d cells\n", check_.path,
                check_.line, TC_N_OUTPUTS);
        return 2;
    }
    for (i = 0; i < TC_N_OUTPUTS; i++) {
        want = value(cells[i], &bad);
        if (bad || !isfinite(want)) {
            fprintf(stderr, "stream: check: %s line %ld: %s is no number\n", check_.path,
                    check_.line, TC_OUTPUT_NAMES[i]);
            return 2;
        }
        diff = fabs(c[i] - want);
        if (!(diff <= check_.um + check_.relative * fabs(want))) {     /* (a NaN fails too) */
            fprintf(stderr, "stream: check failed at input line %ld (row %ld of the stream): "
                    "%s = %.17g, expected %.17g (%s line %ld): |difference| %.3g um beyond the "
                    "tolerance %.3g um + %.3g x |expected|\n", row, check_.rows + 1,
                    TC_OUTPUT_NAMES[i], c[i], want, check_.path, check_.line, diff, check_.um,
                    check_.relative);
            return 1;
        }
        if (diff > check_.worst || check_.worst_line == 0) {
            check_.worst = diff;
            check_.worst_line = row;
            check_.worst_output = i;
        }
    }
    check_.rows++;
    return 0;
}

/* The input ended: 0 when FILE ended too (the largest difference said), else 1. */
static int check_end(long row) {
    if (holds_more(check_.f, check_.path, check_.line, row)) return 1;
    fprintf(stderr, "stream: check passed: %ld rows within %.3g um + %.3g x |expected| of %s "
            "(largest |difference| %.3g um, %s at input line %ld)\n", check_.rows, check_.um,
            check_.relative, check_.path, check_.worst,
            TC_OUTPUT_NAMES[check_.worst_output], check_.worst_line);
    return 0;
}

/* A campaign starts: the compensator's (`reset`: what was learned kept) and its clock's. */
/* (dep107c) the file reader's rules of a record's time (core/io/rates.py), read one row at a time
   as rates.StepWatch reads them for the served model: a campaign's period is the median of its
   first WATCH_STEPS steps; the period changes where most of the last WATCH_STEPS lie RATE_CHANGE
   times from it on one side (said at the first of them; the new period their median); rows are
   missing where one step lies GAP_PERIODS..PAUSE_PERIODS periods long (not an hour and a period)
   and the next is shorter again.  Said on stderr, the corrections not changed: the stream went on
   without a word where replay of the same rows said them (audit107). */
#define WATCH_STEPS 10
#define RATE_CHANGE 2.0
#define GAP_PERIODS 1.5
#define PAUSE_PERIODS 100.0
#define LEARNING_GAP 2.0
static struct {
    double last, period, steps[WATCH_STEPS], gap;
    long rows[WATCH_STEPS], gap_row;
    int n, said_rate, said_gap;
} watch_;

static void watch_reset(void) {
    watch_.last = watch_.period = NAN;
    watch_.n = 0;
    watch_.gap_row = 0;
}

/* The median of the n values of `v` (n <= WATCH_STEPS) for which `pick` is 1 (NULL: all). */
static double median_of(const double *v, const int *pick, int n) {
    double sorted[WATCH_STEPS], x;
    int i, j, m = 0;
    for (i = 0; i < n; i++) {
        if (pick != NULL && !pick[i]) continue;
        for (x = v[i], j = m++; j > 0 && sorted[j - 1] > x; j--) sorted[j] = sorted[j - 1];
        sorted[j] = x;
    }
    return m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
}

/* Whether `step` is a stretch without rows at `period`: not a pause, nor an hour and a period. */
static int watch_long(double step, double period) {
    return step >= GAP_PERIODS * period && step <= PAUSE_PERIODS * period
           && fabs(step - 3600.0 - period) > period / 2;
}

/* The long step waiting (its row, its period) said where the next `step` is short again. */
static void watch_gap_said(double step, double period) {
    if (watch_.gap_row && step < GAP_PERIODS * period && watch_.said_gap++ < 5)
        fprintf(stderr, "stream: line %ld: %.3g sample periods of %g s without rows before this "
                "one (a logger's outage?), as the model's reader says of the same rows: a model "
                "whose lags count samples (arx, lstm) reads them as one period; the corrections "
                "go on%s\n", watch_.gap_row, watch_.gap / period, period,
                watch_.said_gap == 5 ? " (no more said)" : "");
}

static void watched(double t, long row) {
    double step, period = watch_.period;
    int i, side, count, pick[WATCH_STEPS];
    if (!isfinite(t) || (isfinite(watch_.last) && t <= watch_.last)) return;
    step = t - watch_.last;
    watch_.last = t;
    if (!isfinite(step)) return;
    if (watch_.n == WATCH_STEPS) {          /* the last WATCH_STEPS steps */
        memmove(watch_.steps, watch_.steps + 1, (WATCH_STEPS - 1) * sizeof(double));
        memmove(watch_.rows, watch_.rows + 1, (WATCH_STEPS - 1) * sizeof(long));
        watch_.n--;
    }
    watch_.steps[watch_.n] = step;
    watch_.rows[watch_.n++] = row;
    if (!isfinite(period)) {
        /* (con111) the period being learned (rates.StepWatch's _learning): the step before this
           one (not the campaign's first) a stretch where it is LEARNING_GAP times the longest of
           the others, said as replay says it (a few steps of a jittery clock lie 1.5x apart) */
        if (watch_.n >= 3) {
            double most = 0.0, others;
            for (i = 0; i < watch_.n; i++) {
                pick[i] = i != watch_.n - 2;
                if (pick[i] && watch_.steps[i] > most) most = watch_.steps[i];
            }
            others = median_of(watch_.steps, pick, watch_.n);
            watch_.gap_row = watch_.rows[watch_.n - 2];
            watch_.gap = watch_.steps[watch_.n - 2];
            if (watch_.gap >= LEARNING_GAP * most && watch_long(watch_.gap, others))
                watch_gap_said(0.0, others);
            watch_.gap_row = 0;
        }
        if (watch_.n == WATCH_STEPS) {
            watch_.period = median_of(watch_.steps, NULL, watch_.n), watch_.n = 0;
            watch_.gap_row = watch_long(step, watch_.period) ? row : 0;
        }
        return;
    }
    watch_gap_said(step, period);
    watch_.gap_row = watch_long(step, period) ? row : 0;
    watch_.gap = step;
    for (side = 0; side < 2; side++) {
        for (i = count = 0; i < watch_.n; i++)
            count += pick[i] = side ? watch_.steps[i] <= period / RATE_CHANGE
                                    : watch_.steps[i] >= RATE_CHANGE * period;
        if (2 * count <= WATCH_STEPS) continue;
        for (i = 0; !pick[i]; i++) {}
        watch_.period = median_of(watch_.steps, pick, watch_.n);
        if (watch_.said_rate++ < 5)
            fprintf(stderr, "stream: line %ld: the sample period changes from %g s to %g s here "
                    "(the logger set to another rate?), as the model's reader says of the same "
                    "rows: a model whose lags count samples (arx, lstm) reads a sample as %g s "
                    "before it and %g s after; the corrections go on%s\n", watch_.rows[i], period,
                    watch_.period, period, watch_.period, watch_.said_rate == 5 ? " (no more said)" : "");
        watch_.n = 0;
        watch_.gap_row = 0;
        break;
    }
}

static void restart(tc_state *s, int reset) {
    if (reset) tc_reset(s);
    clock_.started = 0;
    watch_reset();
}

/* 1: `line` (not changed), a row under the header, describes the channels (catman70): a cell
   filled, no input's cell a number, or the first cell a label in the time's or an input's
   column (`dt` over seconds). */
static int described(const char *line, const int *where, int time_col) {
    static char copy[MAX_LINE];
    char *cells[MAX_COLS];
    int n, i, bad, filled = 0, number = 0;
    strcpy(copy, line);
    n = split(copy, cells);
    for (i = 0; i < TC_N_INPUTS; i++) {
        if (where[i] < 0 || where[i] >= n || !*trimmed(cells[where[i]])) continue;
        bad = 0;
        filled = 1;
        if (is_mark(cells[where[i]]) || isfinite(value(cells[where[i]], &bad)) || !bad)
            number = 1;
    }
    if (filled && !number) return 1;
    if (n < 1 || !is_label(cells[0])) return 0;
    if (time_col == 0) return 1;
    for (i = 0; i < TC_N_INPUTS; i++)
        if (where[i] == 0) return 1;
    return 0;
}

int main(int argc, char **argv) {
    static char line[MAX_LINE], run[MAX_CELL] = "";
    char *cells[MAX_COLS], *state_path = NULL, *state_tmp = NULL, *end;
    int where[TC_N_INPUTS], error_col[TC_N_OUTPUTS], time_col = -1, reset_col = -1, run_col = -1;
    int word_of[TC_N_INPUTS];   /* an input read from a status word: its TC_WORD_BITS row (-1: none) */
    int twin_col[TC_N_INPUTS];  /* (cin103) a copy of its column the reader refuses apart (-1: none) */
    int twin_head[TC_N_INPUTS]; /* ... its row of TC_TWIN_REFUSED */
    int time_read = TIME_AS_GIVEN;    /* (cin103) --flags' time_read of the row */
    int source_col[TC_N_SOURCES + 1], k;
    double r[TC_N_SOURCES + 1];        /* a row's error columns of derived targets (um) */
    int clock_col = -1;        /* a time of day beside the date (TC_CLOCK_COLUMN): joined */
    static char header_raw[MAX_LINE], units_raw[MAX_LINE], first_row[MAX_LINE], row_raw[MAX_LINE];
    static char units_given[MAX_LINE];   /* (names97b) the unit row the header search read */
    char *raw[MAX_COLS];
    /* a first row read after the header; a header again seen; lines above the header all `#`
       comments (or blank); one of them a `#` comment; the header written as one; `#` lines
       among the rows said */
    int pending = 0, again = 0, commented = 1, noted = 0, hashed = 0, said_hash = 0;
    long blank_at = 0;         /* (audit103) a blank line after a sample: its line, said at the next row */
    int said_blank = 0;
    /* (audit96) the preamble's lines above the header (Excel's `sep=;`, a logger's title), to
       know them written again above it; the line of a row held as one (0: none) */
    static char above[MAX_LINE];
    long held_row = 0;
    static char stamp[2 * MAX_CELL + 2];
    int ambient_col = -1;
    int said_back = 0;         /* rows said whose time is not after the last read */
    int flags = 0;             /* (cflags100) --flags: the monitor's state on each row */
    int back = 0;              /* 1: this row's time is not after the last read */
    int not_after;             /* (cin103) its time not after the last read (back: the first such) */
    int repeating = 0;         /* (dup99) the row before was one written again */
    int said_repeat = 0;       /* (dup99) bursts of rows written again said */
    long footer_at = 0;        /* the first line of a `#` block under the rows (0: none yet) */
    int sampled = 0;           /* a sample row read (rows describing channels are above it) */
    int unit_rowed = 0;        /* a unit row under the header (rows describing channels: below) */
    double ambient = NAN;      /* --ambient: a campaign's initial ambient (TC_AMBIENT_GIVEN) */
    int ncols, i, j, ignored, measured, restored = 0, failed;
    /* the line of the file read last (1: its first), as an editor numbers it: the preamble
       above the header counted (leftovers67); the header's line */
    long row = 1, top = 1;
    tc_state s;
    double u[TC_N_INPUTS], c[TC_N_OUTPUTS], e[TC_N_OUTPUTS], t = NAN;

    for (i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--state") == 0 && i + 1 < argc && argv[i + 1][0]) {
            state_path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--flags") == 0) {
            flags = 1;
            continue;
        }
        if (strcmp(argv[i], "--check-flags") == 0 && i + 1 < argc && argv[i + 1][0]) {
            flags_.path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--check") == 0 && i + 1 < argc && argv[i + 1][0]) {
            check_.path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--ambient") == 0 && i + 1 < argc) {
            ambient = strtod(argv[i + 1], &end);
            if (end != argv[i + 1] && *end == '\0' && isfinite(ambient)) {
                i++;
                continue;
            }
        }
        if ((strcmp(argv[i], "--tolerance") == 0 || strcmp(argv[i], "--relative") == 0)
            && i + 1 < argc) {
            double *to = argv[i][2] == 't' ? &check_.um : &check_.relative;
            *to = strtod(argv[i + 1], &end);
            if (end != argv[i + 1] && *end == '\0' && *to >= 0) {
                i++;
                continue;
            }
        }
        fprintf(stderr, "usage: %s [--state FILE] [--check FILE [--tolerance UM] [--relative R]]"
                " [--check-flags FILE] [--ambient C] [--flags] < rows.csv\n", argv[0]);
        return 2;
    }
    if (check_.path != NULL && !check_open()) return 2;
    if (flags_.path != NULL && !flags_open()) return 2;
    if (state_path != NULL) {
        state_tmp = malloc(strlen(state_path) + 5);
        if (state_tmp == NULL) { fprintf(stderr, "stream: out of memory\n"); return 2; }
        strcpy(state_tmp, state_path);
        strcat(state_tmp, ".tmp");
    }
    if (!next_line(line, sizeof line, 1)) { fprintf(stderr, "stream: no header on stdin\n"); return 2; }
    if (strncmp(line, "\xEF\xBB\xBF", 3) == 0) memmove(line, line + 3, strlen(line + 3) + 1);
    if (strncmp(line, "TDSm", 4) == 0 || (strncmp(line, "MATLAB ", 7) == 0
                                          && strstr(line, "MAT-file") != NULL)) {
        /* a lab's binary log fed as it is: its bytes are no header to name a column of */
        fprintf(stderr, "stream: %s is binary, not read here; convert it to CSV first, as the "
                "export's check/<campaign>/rows.csv are: " ROWS_COMMAND "\n",
                line[0] == 'T' ? "a National Instruments TDMS log" : "a MATLAB .mat file");
        return 2;
    }
    if (line[strspn(line, " \t")] == '{') {
        fprintf(stderr, "stream: line 1 is a JSON object: JSON Lines is not read here; convert "
                "the file to CSV (a header line naming the columns, then one row per sample): "
                ROWS_COMMAND "\n");
        return 2;
    }
    if (strncmp(line, "\"Model\",\"GL", 11) == 0 || strncmp(line, "Model,GL", 8) == 0) {
        /* (stranger82) a Graphtec logger's CSV: its channels named in its Amp settings block,
           its columns CH1 ...: no line of it names the inputs (it was "the header (line 9 ...)
           lacks input column ...", an Amp settings row taken for the header) */
        fprintf(stderr, "stream: line 1 is a Graphtec logger's header block (\"Model\",\"GL...\"): "
                "its channels are named in its Amp settings, its columns CH1 ...; convert it to "
                "the rows the served model reads it as: " ROWS_COMMAND "\n");
        return 2;
    }
    if (strncmp(line, "\"Universal Viewer\"", 18) == 0 || strncmp(line, "Universal Viewer", 16) == 0) {
        /* (stranger82b) a Yokogawa viewer's ASCII export: its Tag row was taken for the header
           and its Tag Comment row refused as a row missing every input, a header written */
        fprintf(stderr, "stream: line 1 is a Yokogawa viewer's header block (\"Universal Viewer\"): "
                "its channels are named in its Tag row, its columns by channel number; convert it "
                "to the rows the served model reads it as: " ROWS_COMMAND "\n");
        return 2;
    }
    if (!names_every_input(line)) {
        /* a logger's preamble (stranger64: `Machine;PM-12`, `Operator: ...` above the header):
           the first of the next MAX_PREAMBLE lines naming every input is the header; (names97b)
           or naming them with the unit row under it (`T;T` over `degC;K`: unit_named) */
        static char first[MAX_LINE], most[MAX_LINE], prev[MAX_LINE];
        int named_most = inputs_named(line), most_row = 1, most_commented = 0, most_noted = 0, n;
        size_t prev_above = 0;          /* (the preamble, `commented`, `noted` above `prev`) */
        int prev_commented = commented, prev_noted = noted;
        strcpy(first, line);
        strcpy(most, line);
        strcpy(prev, line);
        kept(above, line);
        commented = commented && comment_or_blank(line);
        noted = noted || line[strspn(line, " \t")] == '#';
        for (i = 0; i < MAX_PREAMBLE && next_line(line, sizeof line, i + 2); i++) {
            if (strncmp(line, "Channel 1:", 10) == 0 || strncmp(line, "Kanal 1:", 8) == 0) {
                /* (stranger84) HBM catman's ASCII export with its channel header: its table
                   starts below a block a channel (over 100 lines); line 1, `File:`, was taken
                   for the header and an input said missing that the file holds */
                fprintf(stderr, "stream: line %d is HBM catman's channel block (%s:): its channels "
                        "are named in blocks above the table; convert it to the rows the served "
                        "model reads it as: " ROWS_COMMAND "\n", i + 2,
                        line[0] == 'C' ? "Channel 1" : "Kanal 1");
                return 2;
            }
            if (inputs_named_over(prev, line) == TC_N_INPUTS) {
                strcpy(units_given, line);        /* the header's unit row, read */
                strcpy(line, prev);
                above[prev_above] = '\0';
                commented = prev_commented, noted = prev_noted;
                break;
            }
            if ((n = inputs_named(line)) == TC_N_INPUTS) break;
            prev_above = strlen(above), prev_commented = commented, prev_noted = noted;
            kept(above, line);
            if (n > named_most)      /* (the lines above it: comments, a '#' among them?) */
                named_most = n, most_row = i + 2, most_commented = commented,
                most_noted = noted, strcpy(most, line);
            commented = commented && comment_or_blank(line);
            noted = noted || line[strspn(line, " \t")] == '#';
            strcpy(prev, line);
        }
        if (units_given[0])
            row = i + 1;                          /* the header's line, its unit row's under it */
        else if (i < MAX_PREAMBLE && names_every_input(line))
            row = i + 2;                          /* the header's line */
        else {
            above[0] = '\0';                      /* (no header found: no preamble known) */
            if (most_row > 1)
                /* (stranger73) no line names every input: the one naming the most is the
                   header whose missing input is said (line 1, a preamble's, was, naming the
                   first input of all as missing) */
                strcpy(line, most), row = most_row, commented = most_commented,
                    noted = most_noted;
            else
                strcpy(line, first), commented = 1, noted = 0;
        }
    }
    sep = separator_of(line);
    strcpy(header_raw, line);
    header_raw[strcspn(header_raw, "\r\n")] = '\0';
    ncols = split(line, cells);
    /* (stranger66) a header written as a comment under a block of them (a DAQ script's
       `# t [s]<TAB>T1 [degC]`, numpy's savetxt): its first name without the `#`, as the reader
       reads it; a first column named `#` alone stays */
    if (commented && ncols > 0 && cells[0][0] == '#' && *uncommented(cells[0]))
        cells[0] = uncommented(cells[0]), hashed = 1;
    for (j = 0; j < ncols; j++) raw[j] = cells[j];
    for (j = 0, k = 0; j < ncols; j++) k += strcmp(cells[j], "Name") == 0;
    if (k > 1) {
        /* (stranger76) a TwinCAT Scope export's row of channel names (`Name;T1;;Name;T2;`): its
           property rows under it would be read as samples, a correction printed of them.
           (lab77) Refused, not read: its channels' times are merged over the whole file and a
           temperature's cell at another clock's time interpolated from the sample after it,
           which a stream of rows cannot; the command that writes the table the served model
           reads it as is named */
        fprintf(stderr, "stream: line %ld is a TwinCAT Scope export's row of channel names "
                "(Name;<channel>;;Name;...): the export is not read here; convert it to the "
                "rows the served model reads it as: " ROWS_COMMAND "\n", row);
        return 2;
    }
    for (j = 0; j < ncols; j++) cells[j] = (char *)named(twin(raw, j), j);
    /* (streamraw65) a unit row under the header (`;;degC;W;-;um`: every cell it fills no number,
       an input's among them), as the reader reads it: left out, each header joined to its unit
       (`T Halle [degC]`) */
    top = row;
    if (units_given[0]) strcpy(units_raw, units_given), pending = 1;   /* (read by the search) */
    else pending = next_line(units_raw, sizeof units_raw, row + 1);
    if (pending) {
        if (unit_named(raw, ncols, units_raw, (const char **)cells)) {
            pending = 0;
            unit_rowed = 1;
            row++;
            units_raw[strcspn(units_raw, "\r\n")] = '\0';
        } else {
            strcpy(first_row, units_raw);   /* the first row: read in the loop */
            units_raw[0] = '\0';
        }
    }
    for (j = 0; j < ncols; j++) {
        if (TC_RUN_COLUMN[0] && strcmp(cells[j], TC_RUN_COLUMN) == 0) run_col = j;
        if (TC_CLOCK_COLUMN[0] && strcmp(cells[j], TC_CLOCK_COLUMN) == 0) clock_col = j;
    }
    for (i = 0; i < TC_N_INPUTS; i++) {
        where[i] = -1;
        for (j = 0; j < ncols; j++) {
            if (strcmp(cells[j], TC_INPUT_NAMES[i]) != 0) continue;
            if (where[i] >= 0) {
                fprintf(stderr, "stream: the header names input %s twice (columns %d and %d)\n",
                        TC_INPUT_NAMES[i], where[i] + 1, j + 1);
                return 2;
            }
            where[i] = j;
        }
        word_of[i] = -1;
        for (k = 0; k < TC_N_WORD_BITS; k++) {
            /* (lead91; bits85 refused it) a bit of a PLC's status word (data.bits), the word
               given in its place: read from the word, as the reader and the served model
               decode it; the word and the bit both given refused, as served refuses them */
            if (strcmp(TC_INPUT_NAMES[i], TC_WORD_BITS[k][0]) != 0) continue;
            for (j = 0; j < ncols && strcmp(raw[j], TC_WORD_BITS[k][1]) != 0; j++) {}
            if (j == ncols && where[i] >= 0) break;
            if (j == ncols) {
                fprintf(stderr, "stream: the header (line %ld) lacks input column %s, bit %d of "
                        "the PLC status word '%s' (data.bits), and the word: give either, the "
                        "word as the controller logs it or each bit as a column of its own, as "
                        "thermocomp rows writes them\n", top, TC_INPUT_NAMES[i], TC_WORD_BIT[k],
                        TC_WORD_BITS[k][1]);
                return 2;
            }
            if (where[i] >= 0) {
                fprintf(stderr, "stream: the header (line %ld) gives the status word '%s' "
                        "(column %d) and its bit %s (column %d) both (data.bits): send one "
                        "of them\n", top, TC_WORD_BITS[k][1], j + 1, TC_INPUT_NAMES[i],
                        where[i] + 1);
                return 2;
            }
            where[i] = j;
            word_of[i] = k;
        }
        if (where[i] < 0) {
            /* a lab's report or gateway file fed as it is (a title line read as the header):
               what the stream reads, said with the missing name */
            const char *lab = lab_header(TC_INPUT_NAMES[i]);
            fprintf(stderr, "stream: the header (line %ld: CSV naming the inputs as TC_INPUT_NAMES "
                    "in compensator.h does, in degC%s; a file in fixed-width columns, JSON "
                    "Lines, a historian's or InfluxDB export, a TwinCAT Scope export: converted "
                    "first, to CSV, as the export's check/<campaign>/rows.csv are, by thermocomp "
                    "rows) lacks input column %s%s%s%s\n", top,
                    TC_LAB_NAMES[0][0][0] ? ", or by a lab's header TC_LAB_NAMES lists, in its "
                    "unit" : "", TC_INPUT_NAMES[i], lab[0] ? " (the lab's header '" : "", lab,
                    lab[0] ? "')" : "");
            return 2;
        }
    }
    for (j = 0; j < ncols; j++)
        if (alike_of[j][0] >= 0) {
            /* (names97) a bare header two of the model's columns share but for their unit, no
               unit row under it: refused naming both, as the served model refuses it (it was
               read as the first, which may be the other column) */
            fprintf(stderr, "stream: the header (line %ld), column %d: '%s' may be '%s' or '%s': "
                    "two columns alike but for their unit; send the header with its unit\n", top,
                    j + 1, trimmed(raw[j]), TC_LAB_NAMES[alike_of[j][0]][0],
                    TC_LAB_NAMES[alike_of[j][1]][0]);
            return 2;
        }
    /* (cin103) an input's header written again (no unit row: the same text), the copy no input
       of the model: the reader leaves it out where each of its cells equals the first's; where
       one differs it refuses the file (which is the sensor?) if the copy is read by no role
       pattern nor data.columns (TC_TWIN_REFUSED: the inputs' contract names), else reads it under
       a name of its own (a lab's roles-read file: `T Luft#2 [degC]` as T_Luft_2) and the input
       from the first column, as here.  Compared row by row below (the stream read the first on) */
    for (i = 0; i < TC_N_INPUTS; i++) {
        twin_col[i] = -1;
        twin_head[i] = unit_rowed || where[i] < 0 || word_of[i] >= 0 ? -1
                       : twin_refused(trimmed(raw[where[i]]));
        for (j = where[i] + 1; twin_head[i] >= 0 && j < ncols && twin_col[i] < 0; j++) {
            if (strcmp(trimmed(raw[j]), TC_TWIN_REFUSED[twin_head[i]]) != 0) continue;
            for (k = 0; k < TC_N_INPUTS && where[k] != j; k++) {}
            if (k == TC_N_INPUTS) twin_col[i] = j;
        }
    }
    for (i = 0; i < TC_N_OUTPUTS; i++) {
        error_col[i] = -1;
        for (j = 0; TC_ADAPT && j < ncols; j++)
            if (strcmp(cells[j], TC_ERROR_NAMES[i]) == 0) error_col[i] = j;
    }
    for (k = 0; k < TC_N_SOURCES; k++) {   /* a derived target's error columns (data.derive) */
        source_col[k] = -1;
        for (j = 0; TC_ADAPT && j < ncols; j++)
            if (strcmp(cells[j], TC_SOURCE_NAMES[k]) == 0) source_col[k] = j;
    }
    for (j = 0; j < ncols; j++) {
        if (strcmp(cells[j], "time") == 0) time_col = j;
        if (strcmp(cells[j], "reset") == 0) reset_col = j;
        if (strcmp(cells[j], "ambient_c") == 0) ambient_col = j;
    }
    if (TC_AMBIENT_GIVEN && !TC_AMBIENT_OPTIONAL && ambient_col < 0 && !isfinite(ambient)) {
        fprintf(stderr, "stream: the model picks its laws by a campaign's initial ambient and "
                "reads no ambient sensor: give it in an ambient_c column (degC, on a campaign's "
                "first row: the manifest's ambient_c) or as --ambient C\n");
        return 2;
    }
    if (TC_USES_TIME && time_col < 0)
        fprintf(stderr, "stream: no time column: samples taken one period apart\n");
    for (i = 0; i < TC_N_OUTPUTS; i++) printf("%s%s", i ? "," : "", TC_OUTPUT_NAMES[i]);
    if (flags) printed_flags(NULL, 0);
    printf("\n");
    tc_init(&s);
    watch_reset();
    if (state_path != NULL && (restored = restore_state(state_path, &s, run)) < 0) {
        fprintf(stderr, "stream: %s is no state this build wrote (another model or compiler?): "
                "remove it to start cold\n", state_path);
        return 2;
    }
    if (restored && state_blank) blank_at = -1;   /* (dep107b) the last input ended on a blank line */
    while (pending || next_line(line, sizeof line, row + 1)) {
        if (pending) strcpy(line, first_row), pending = 0;
        row++;
        /* (audit96) a line of the preamble written again above the header (a second export
           appended to the first: Excel's `sep=;` above it), not of the header's width: held,
           and left out with the header under it, as the reader leaves it out (stranger66); any
           other line under it refuses it, as before */
        if (above[0] && line[strspn(line, " \t")] != '#' && among(above, strip_end(line))) {
            strcpy(row_raw, line);
            if (split(row_raw, cells) != ncols) {
                if (!held_row) held_row = row;
                continue;
            }
        }
        if (held_row && strcmp(strip_end(line), header_raw) != 0) {
            fprintf(stderr, "stream: line %ld has not %d cells\n", held_row, ncols);
            return 2;
        }
        if (held_row)
            fprintf(stderr, "stream: line %ld: the file's preamble written again above its header "
                    "(a second export appended?): left out\n", held_row);
        held_row = 0;
        /* (streamraw65) the header written again (a logger restarted), the unit row under it
           too: left out, as the reader leaves it out, and said (the rows after it go on) */
        if (strcmp(strip_end(line), header_raw) == 0) {
            fprintf(stderr, "stream: line %ld: the header written again (a logger restarted?): "
                    "left out\n", row);
            again = units_raw[0] != '\0';
            continue;
        }
        if (again && strcmp(line, units_raw) == 0) {
            again = 0;
            continue;
        }
        again = 0;
        /* (stranger66, leftovers67) a `#` line among the rows of a file that writes `#` comments
           (its lines above the header, or its header): a logger's note, the DAQ's block written
           again with its header (a restart); left out as the reader leaves it out */
        if ((hashed || (commented && noted)) && line[strspn(line, " \t")] == '#') {
            if (said_hash++ < 5)
                fprintf(stderr, "stream: line %ld: a '#' comment among the rows (the file writes "
                        "'#' comments: a logger's note?): left out%s\n", row,
                        said_hash == 5 ? " (no more said)" : "");
            continue;
        }
        /* (catman70) a row describing the channels under the header's unit row, before the
           first sample: catman's channel comments or T0 row (no input cell a number), its
           dt row (a label in the first column, the time's or an input's): left out */
        if (unit_rowed && !sampled && row - top <= MAX_PROPERTY_ROWS + 1
            && described(line, where, time_col))
            continue;
        strcpy(row_raw, line);
        /* (stranger75) a `#` line of other than the header's width: a logger's run summary
           under the rows, left out where only `#` lines (or blank ones) follow it, as the
           reader leaves a footer out; a row after it: refused at the `#` line, as before */
        if (line[strspn(line, " \t")] == '#' && split(row_raw, cells) != ncols) {
            if (!footer_at) footer_at = row;
            strcpy(row_raw, line);
            continue;
        }
        if (footer_at && line[strspn(line, " \t\r\n")] == '\0') continue;
        if (footer_at) {
            fprintf(stderr, "stream: line %ld has not %d cells: a '#' line among the rows: a "
                    "comment? a '#' line is left out as one only in a file that writes '#' "
                    "comments (its lines above the header, or its header itself), or in a block "
                    "under the rows\n", footer_at, ncols);
            return 2;
        }
        if (line[strspn(line, " \t\r\n")] == '\0') {
            if (sampled || restored) {   /* (dep107b) decided at the next row, by its time (below) */
                if (!blank_at) blank_at = row;
                continue;
            }
            restart(&s, 1);
            if (!saved(state_path, state_tmp, &s, run)) return 2;
            continue;
        }
        sampled = 1;
        if (split(line, cells) != ncols) {
            fprintf(stderr, "stream: line %ld has not %d cells\n", row, ncols);
            return 2;
        }
        for (i = 0; i < TC_N_INPUTS; i++)
            if (twin_col[i] >= 0
                && strcmp(trimmed(cells[where[i]]), trimmed(cells[twin_col[i]])) != 0) {
                /* (cin103) replay's words (roles.naming); the rows above printed, a stream */
                fprintf(stderr, "stream: line %ld: columns %d and %d have the same header '%s', "
                        "different values ('%s', '%s'): name the second, data.columns={'%s': "
                        "T_<name>}, and fit and export again (the model's reader refuses the "
                        "file, as replay does: which is input %s's sensor?)\n", row, where[i] + 1,
                        twin_col[i] + 1, TC_TWIN_REFUSED[twin_head[i]], trimmed(cells[where[i]]),
                        trimmed(cells[twin_col[i]]), twins[twin_col[i]], TC_INPUT_NAMES[i]);
                return 2;
            }
        if (reset_col >= 0 && value(cells[reset_col], &ignored) == 1.0) restart(&s, 1);
        if (run_col >= 0 && strcmp(cells[run_col], run) != 0) {    /* the next run */
            /* (not at the first line under the header; a restored stream was in another run) */
            restart(&s, row > top + 1 || restored);
            strncpy(run, cells[run_col], MAX_CELL - 1);
        }
        for (i = 0; i < TC_N_INPUTS; i++) {
            int bad = 0;
            u[i] = converted(cells, where[i], &bad);
            if (word_of[i] >= 0 && isfinite(u[i])) {
                /* the reader's rule (core/io/bits.py): a whole number >= 0 below 2^63 */
                if (u[i] < 0 || u[i] != floor(u[i]) || u[i] >= 9223372036854775808.0) {
                    fprintf(stderr, "stream: line %ld, column %d ('%s'): value %g is no whole "
                            "number >= 0: no status word (data.bits)\n", row, where[i] + 1,
                            TC_WORD_BITS[word_of[i]][1], u[i]);
                    return 2;
                }
                u[i] = (double)(((unsigned long long)u[i] >> TC_WORD_BIT[word_of[i]]) & 1ULL);
            }
            /* another header: one naming every input, or (audit105) at least half of them, the
               rest renamed (`T_hall_new` was refused as "no number", no word of a header) */
            if (bad && 2 * inputs_named(row_raw) >= TC_N_INPUTS) {   /* (sets sep: the same) */
                fprintf(stderr, "stream: line %ld is a header other than the first (another "
                        "file's: a column renamed?)", row);
                if (unnamed_input >= 0 && where[unnamed_input] >= 0)
                    fprintf(stderr, ": column %d reads '%s' where the header named input %s",
                            where[unnamed_input] + 1, trimmed(cells[where[unnamed_input]]),
                            TC_INPUT_NAMES[unnamed_input]);
                fprintf(stderr, ": stream each file by itself, --state FILE carries the campaign "
                        "from one to the next\n");
                return 2;
            }
            if (bad && decimal_comma(cells[where[i]])) {
                /* (dep107c) a decimal comma where the separator is ',': the reader's hint, not a
                   missing value's (audit107: `22,61` was asked to be a mark) */
                fprintf(stderr, "stream: line %ld: input %s: '%s' is no number: a decimal comma? "
                        "this stream separates its cells with ',' and reads decimal points; a "
                        "stream with decimal commas separates them with ';', a tab or '|'\n",
                        row, TC_INPUT_NAMES[i], trimmed(cells[where[i]]));
                return 2;
            }
            if (bad) {    /* (streamraw65: read as missing before; the reader refuses it) */
                fprintf(stderr, "stream: line %ld: input %s: '%s' is no number (a mark for a "
                        "value not measured? the model's data.missing_values lists %d)\n", row,
                        TC_INPUT_NAMES[i], trimmed(cells[where[i]]), TC_N_MISSING);
                return 2;
            }
            if (isfinite(u[i]) && fabs(u[i]) > TC_INPUT_LIMIT[i]) {   /* (a temperature's) */
                /* (faults71) as the reader refuses it: a Keysight DAQ's +9.9E+37 was read as
                   a temperature and clamped, corrections off by up to the whole correction */
                fprintf(stderr, "stream: line %ld: input %s: %g degC is beyond %g degC, which no "
                        "sensor reads: the logger's mark for an overload or an open circuit? "
                        "the reader refuses it; list it in the model's data.missing_values (a "
                        "value not measured)\n", row, TC_INPUT_NAMES[i], u[i], TC_INPUT_LIMIT[i]);
                return 2;
            }
            if (!isfinite(u[i]) && !TC_INPUT_HELD[i] && !monitored(i)) {
                /* (a held signal: tc_step holds it; a monitored sensor's: its monitor, cdrop77) */
                fprintf(stderr, "stream: line %ld: input %s has no finite value%s\n", row,
                        TC_INPUT_NAMES[i], is_mark(cells[where[i]]) ? " (a data.missing_values "
                        "mark: a missing value, which the plain stream refuses as replay's does)"
                        : "");
                return 2;
            }
        }
        if (time_col >= 0 && clock_col >= 0)      /* '07.06.2027' and '14:00:00': one time */
            snprintf(stamp, sizeof stamp, "%s %s", trimmed(cells[time_col]),
                     trimmed(cells[clock_col]));
        if (row_time(cells, time_col, clock_col, stamp, row, &t) != 0) return 2;
        if (blank_at) {
            /* (dep107b) a blank line after a sample starts a campaign where the row after it has
               no time or one not after the last read (the campaigns thermocomp rows writes, each
               from its time 0; monitor.input=- reads them so); a blank line within a run, its
               time going on, is nothing, as run, replay and the served stream on stdin read it
               (audit103 said it and restarted there: a lab's mlr 35.7 um off at once) */
            /* (dep108b) without a time column no time tells a campaign's start: the blank line
               is left out, the rows after it one period on, as the file reader and stdin read it
               (the data contract's; it restarted here: col10133's mlr 281 um off) */
            int timeless = time_col < 0 && clock_col < 0;
            int goes_on = timeless || (isfinite(t) && !s.first && isfinite(s.t_read) && t > s.t_read
                                       && !(TC_DAY_SECONDS && day_passed));  /* (a day gone back) */
            char at[64];
            if (blank_at < 0) strcpy(at, "the last input's end (--state)");
            else snprintf(at, sizeof at, "line %ld", blank_at);
            if (said_blank++ < 5)
                fprintf(stderr, "stream: %s: a blank line: %s%ld%s%s\n", at, timeless
                        ? "left out, no time column: the rows from line " : goes_on
                        ? "read as nothing, the time going on at line " : "a new campaign starts "
                          "at line ", row, timeless ? " read one period after the row above it, as "
                          "run, replay and monitor.input=- read them (a sample not taken: leave its "
                          "cells empty instead)" : goes_on ? " (a stray blank line within a run), as "
                          "run, replay and the served stream read it" : " (the state reset, that row "
                          "the reference: its time is not after the last read, as between the "
                          "campaigns thermocomp rows writes)", said_blank == 5 ? " (no more said)" : "");
            blank_at = state_blank = 0;
            if (!goes_on) {
                restart(&s, 1);
                if (row_time(cells, time_col, clock_col, stamp, row, &t) != 0) return 2;
            }
        }
        if (TC_PAUSE_S > 0 && isfinite(t) && !s.first && isfinite(s.t_read)
            && t - s.t_read > TC_PAUSE_S) {
            /* (catman70) the logger silent longer than data.runs_at_pauses' pause: the next
               test, a campaign of its own (as the reader splits the file), its clock from here */
            restart(&s, 1);
            if (row_time(cells, time_col, clock_col, stamp, row, &t) != 0) return 2;
        }
        not_after = TC_SUBSTITUTE_TIME && isfinite(t) && !s.first && isfinite(s.t_read)
                    && t <= s.t_read;
        back = not_after && !isfinite(s.t_back);
        /* (cin103) the time rule's verdict (timerule.py, as C_TIME_RULE takes it in tc_step) */
        time_read = time_col >= 0 && !isfinite(t) ? TIME_NONE
                    : not_after && !(isfinite(s.t_back) && t > s.t_back) ? TIME_NOT_AFTER
                    : TIME_AS_GIVEN;
        if (TC_AMBIENT_GIVEN && s.first) {     /* the campaign's ambient, at its first row */
            double a0 = ambient_col >= 0 ? value(cells[ambient_col], &ignored) : NAN;
            if (!isfinite(a0)) a0 = ambient;
            if (!isfinite(a0) && !TC_AMBIENT_OPTIONAL) {
                fprintf(stderr, "stream: line %ld starts a campaign without its ambient_c (and no "
                        "--ambient)\n", row);
                return 2;
            }
            tc_set_ambient(&s, a0);
        }
        repeating = s.repeated;
        if (tc_step(&s, u, t, c) < 0 && TC_MONITOR && s.mon_rule) {
            /* (cdrop77) a monitored sensor's missing reading its monitor cannot rebuild here */
            fprintf(stderr, "stream: line %ld: input %s has no finite value, which the code's "
                    "sensor monitor does not rebuild here (%s): the row is refused (the served "
                    "model rebuilds it)\n", row, TC_INPUT_NAMES[TC_MONITORED[s.mon_sensor]],
                    TC_MONITOR_REASONS[s.mon_rule]);
            return 2;
        }
        if (s.repeated && !repeating && said_repeat++ < 5)
            /* (dup99) a row written again (timerule.repeats): skipped, said at a burst's first */
            fprintf(stderr, "stream: line %ld: the same time (%.10g s) and values as the row "
                    "before it (a row written again): skipped, the last corrections given again "
                    "(as the served model; run refuses a time that repeats)%s\n", row, t,
                    said_repeat == 5 ? " (no more said)" : "");
        if (back && !s.repeated && said_back++ < 5)
            /* (restart66) the time rule (timerule.py): said where it sets in */
            /* (lab77) a date and time without an offset set back by up to an hour: said as the
               reader says it (its 'the clock set back by an hour, daylight saving time
               ending?'), with what this program reads instead of data.timezone */
            fprintf(stderr, "stream: line %ld: the time (%.10g s) is not after the last read (%.10g "
                    "s)%s: taken one period after the previous row; where the next time is after "
                    "this one (a clock started again: a file of the record whose time starts at 0 "
                    "again), the stream counts on with it, as run joins a file that continues "
                    "another; a new campaign starts at a blank line%s\n", row, t, s.t_read,
                    clock_.kind == LOCAL_TIME && s.t_read - t <= 3600.0 ? ": the clock set back "
                    "by an hour, daylight saving time ending? this stream reads no data.timezone "
                    "(a logger's own clock, as the served model): give the times with their "
                    "offset (2026-10-25T02:00:00+01:00) or in UTC" : "",
                    said_back == 5 ? " (no more said)" : "");
        if (time_read == TIME_AS_GIVEN && !s.repeated) watched(t, row);
        if (TC_MONITOR && !s.repeated) said_monitor(&s, row);
        for (i = 0; i < TC_N_OUTPUTS; i++) printf("%s%.17g", i ? "," : "", c[i]);
        if (flags) printed_flags(&s, s.repeated ? TIME_REPEATED : time_read);
        printf("\n");
        if (check_.f != NULL && (failed = check_row(row, c)) != 0) {
            fflush(stdout);
            return failed;
        }
        if (flags_.f != NULL && (failed = flags_row(row, &s)) != 0) {
            fflush(stdout);
            return failed;
        }
        for (k = 0; k < TC_N_SOURCES; k++)
            r[k] = source_col[k] >= 0 ? converted(cells, source_col[k], &ignored) : NAN;
        for (i = measured = 0; i < TC_N_OUTPUTS; i++) {
            /* a derived target's reference: the reader's arithmetic of its error columns where
               the row does not carry it (small72); no number (a missing one): not measured */
            e[i] = error_col[i] >= 0 ? converted(cells, error_col[i], &ignored)
                                     : TC_DERIVED_REFERENCE(i, r);
            if (!isfinite(e[i])) e[i] = NAN;
            measured |= isfinite(e[i]);
        }
        if (measured) tc_reference(&s, e);
        if (!saved(state_path, state_tmp, &s, run)) return 2;
    }
    if (blank_at) {                 /* blank lines at the end: kept for the next row (dep107b) */
        state_blank = 1;
        if (!saved(state_path, state_tmp, &s, run)) return 2;
    }
    if (held_row) {                 /* (audit96) the preamble's line last: refused, as before */
        fprintf(stderr, "stream: line %ld has not %d cells\n", held_row, ncols);
        return 2;
    }
    if (footer_at)
        fprintf(stderr, "stream: lines %ld-%ld: a '#' block under the rows (a logger's summary): "
                "left out\n", footer_at, row);
    failed = check_.f != NULL ? check_end(row) : 0;
    return failed ? failed : flags_.f != NULL ? flags_end(row) : 0;
}
"""
