/* The C ABI from C: hostile inputs get status codes, one template is evaluated from many
 * threads at once, random access equals the batch. Run by capi/tests/c.rs (plain and under
 * valgrind). Prints "ok N checks" and exits 0, or names the failed check and exits 1. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rotlang.h"

static int checks, failures;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        checks++;                                                                     \
        if (!(cond)) {                                                                \
            failures++;                                                               \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                             \
    } while (0)

#define STATUS(call, expected) CHECK((call) == (expected))

static RotlangTemplate *parse(const char *text) {
    RotlangTemplate *t = NULL;
    STATUS(rotlang_parse(text, strlen(text), ROTLANG_TARGET_SPARSE, &t), ROTLANG_STATUS_OK);
    return t;
}

/* ROTLANG_TO_TOP is SIZE_MAX: a size_t, not the signed int `~0` (which is -1). */
_Static_assert(ROTLANG_TO_TOP > 0 && sizeof(ROTLANG_TO_TOP) == sizeof(size_t) && ROTLANG_TO_TOP == SIZE_MAX,
               "ROTLANG_TO_TOP is SIZE_MAX");

static void versions(void) {
    CHECK(rotlang_abi_version() == ROTLANG_ABI_VERSION);
    CHECK(strlen(rotlang_version()) >= 5);
    CHECK(strcmp(rotlang_status_message(ROTLANG_STATUS_BUFFER_TOO_SMALL),
                 "an output buffer is too small for the layer range") == 0);
    CHECK(strcmp(rotlang_status_message(9999), "unknown status") == 0);
    CHECK(strcmp(rotlang_status_message(9), "unknown status") == 0); /* no status 9 */
    CHECK(strcmp(rotlang_status_message(ROTLANG_STATUS_INTERNAL), "internal error in rotlang (please report it)") == 0);
    CHECK(strcmp(rotlang_finding_code(ROTLANG_FINDING_KIND_NAN), "orcaslicer::nan") == 0);
}

/* The documentation's example: "5, 10!, +20" on the 20 mm cube. */
static void evaluates(void) {
    RotlangTemplate *t = parse("5, 10!, +20");
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0);
    double angles[100];
    uint8_t fills[100];
    RotlangFindings findings = {NULL, 0, 99};
    STATUS(rotlang_expand(t, &cube, NULL, 0, ROTLANG_TO_TOP, angles, fills, 100, &findings),
           ROTLANG_STATUS_OK);
    const double expected[7] = {5, 10, 30, 5, 25, 5, 25};
    for (int i = 0; i < 7; i++) CHECK(angles[i] == expected[i]);
    CHECK(fills[0] == ROTLANG_FILL_SPARSE && findings.count == 0);

    /* A range, and the base direction. */
    RotlangOptions options = {45.0, 0, ROTLANG_DIALECT_ROTLANG};
    double range[3];
    STATUS(rotlang_expand(t, &cube, &options, 2, 3, range, NULL, 3, NULL), ROTLANG_STATUS_OK);
    CHECK(range[0] == 75 && range[1] == 50 && range[2] == 70);

    /* One layer, and the evaluator in shuffled order equals the batch. */
    double one = 0;
    STATUS(rotlang_angle_at(t, &cube, NULL, 4, &one, NULL), ROTLANG_STATUS_OK);
    CHECK(one == 25);
    RotlangEvaluator *e = NULL;
    STATUS(rotlang_evaluator_new(t, &cube, NULL, &e), ROTLANG_STATUS_OK);
    for (size_t k = 0; k < 300; k++) {
        size_t i = (k * 37) % 100;
        RotlangLayer layer;
        STATUS(rotlang_evaluator_layer(e, i, &layer), ROTLANG_STATUS_OK);
        CHECK(layer.index == i && layer.angle == angles[i]);
        CHECK(fabs(layer.top - 0.2 * (double)(i + 1)) < 1e-9);
    }
    /* The evaluator keeps its template alive: free the template first. */
    STATUS(rotlang_template_free(t), ROTLANG_STATUS_OK);
    RotlangLayer last;
    STATUS(rotlang_evaluator_layer(e, 99, &last), ROTLANG_STATUS_OK);
    CHECK(last.angle == angles[99]);
    STATUS(rotlang_evaluator_layer(e, 100, &last), ROTLANG_STATUS_OUT_OF_RANGE);
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_OK);
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_INVALID_HANDLE);
}

/* Diagnostics with byte spans: `°` (an error) is bytes 3..5, so the X sits at byte 7. */
static void diagnostics(void) {
    const char *text = "+30°, X";
    RotlangTemplate *t = parse(text);
    size_t n = 0;
    int errors = 0;
    STATUS(rotlang_template_diagnostic_count(t, &n), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_has_errors(t, &errors), ROTLANG_STATUS_OK);
    CHECK(n == 2 && errors == 1);
    RotlangDiagnostic d;
    STATUS(rotlang_template_diagnostic(t, 0, &d), ROTLANG_STATUS_OK);
    CHECK(d.severity == ROTLANG_SEVERITY_ERROR && strcmp(d.code, "rotlang::degree-sign") == 0);
    CHECK(d.start == 3 && d.end == 5 && d.help != NULL);
    STATUS(rotlang_template_diagnostic(t, 1, &d), ROTLANG_STATUS_OK);
    CHECK(strcmp(d.code, "rotlang::unknown-sign") == 0);
    CHECK(d.start == 7 && d.end == 8 && strcmp(d.message, "unknown sign `X`") == 0);
    STATUS(rotlang_template_diagnostic(t, n, &d), ROTLANG_STATUS_OUT_OF_RANGE);
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0);
    double angles[100];
    STATUS(rotlang_expand(t, &cube, NULL, 0, ROTLANG_TO_TOP, angles, NULL, 100, NULL),
           ROTLANG_STATUS_TEMPLATE_HAS_ERRORS);
    char why[256];
    size_t len = rotlang_last_error(why, sizeof why);
    CHECK(len == strlen(why) && strstr(why, "diagnostics") != NULL);
    CHECK(rotlang_last_error(NULL, 0) == len);
    char tiny[4];
    CHECK(rotlang_last_error(tiny, sizeof tiny) == len && strlen(tiny) == 3);
    STATUS(rotlang_template_free(t), ROTLANG_STATUS_OK);
}

/* The OrcaSlicer dialect: any text, OrcaSlicer's angles, its defects as findings. */
static void orcaslicer(void) {
    RotlangOptions orca = {0, 0, ROTLANG_DIALECT_ORCASLICER};
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0);
    double angles[100];
    RotlangFinding items[4];
    RotlangFindings findings = {items, 4, 0};

    /* `10!, 5*` makes OrcaSlicer loop forever from layer 1; rotlang holds the angle. */
    RotlangTemplate *hang = parse("10!, 5*");
    STATUS(rotlang_expand(hang, &cube, &orca, 0, ROTLANG_TO_TOP, angles, NULL, 100, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 1 && items[0].kind == ROTLANG_FINDING_KIND_HANGS);
    CHECK(items[0].first_layer == 1 && items[0].layers == 99);
    CHECK(angles[0] == 10 && angles[1] == 10 && angles[99] == 10);
    /* Not enough room: the count still says how many there are. */
    RotlangFindings none = {NULL, 0, 0};
    STATUS(rotlang_expand(hang, &cube, &orca, 0, ROTLANG_TO_TOP, angles, NULL, 100, &none), ROTLANG_STATUS_OK);
    CHECK(none.count == 1);
    /* Findings only cover the layers evaluated: layer 0 alone has no hang yet. */
    STATUS(rotlang_expand(hang, &cube, &orca, 0, 1, angles, NULL, 1, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 0);
    RotlangEvaluator *e = NULL;
    STATUS(rotlang_evaluator_new(hang, &cube, &orca, &e), ROTLANG_STATUS_OK);
    RotlangLayer layer;
    STATUS(rotlang_evaluator_layer(e, 50, &layer), ROTLANG_STATUS_OK);
    CHECK(layer.angle == 10);
    STATUS(rotlang_evaluator_findings(e, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 1 && items[0].kind == ROTLANG_FINDING_KIND_HANGS);
    /* Going back reopens the stream: the findings of the layers gone through stay. */
    STATUS(rotlang_evaluator_layer(e, 0, &layer), ROTLANG_STATUS_OK);
    findings.count = 99;
    STATUS(rotlang_evaluator_findings(e, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 1 && items[0].kind == ROTLANG_FINDING_KIND_HANGS && items[0].first_layer == 1);
    STATUS(rotlang_evaluator_layer(e, 70, &layer), ROTLANG_STATUS_OK);
    STATUS(rotlang_evaluator_findings(e, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 1 && items[0].layers == 99);
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_OK);

    /* A bad findings output fails the call before anything is written. */
    RotlangFindings no_items = {NULL, 4, 77};
    angles[0] = -1;
    STATUS(rotlang_expand(hang, &cube, &orca, 0, ROTLANG_TO_TOP, angles, NULL, 100, &no_items),
           ROTLANG_STATUS_NULL_POINTER);
    CHECK(angles[0] == -1 && no_items.count == 77);
    uint8_t fill = 99;
    double one = -1;
    STATUS(rotlang_angle_at(hang, &cube, &orca, 100, &one, &fill), ROTLANG_STATUS_OUT_OF_RANGE);
    CHECK(one == -1 && fill == 99);
    STATUS(rotlang_template_free(hang), ROTLANG_STATUS_OK);

    /* NaN in OrcaSlicer (`$` of a first layer thinner... see SEMANTICS 10): reported, and
     * rotlang's angles stay finite. */
    RotlangTemplate *nan = parse("+22.5$50%");
    RotlangModel thick_first = rotlang_model_uniform(100, 0.2, 0.3);
    STATUS(rotlang_expand(nan, &thick_first, &orca, 0, ROTLANG_TO_TOP, angles, NULL, 100, &findings),
           ROTLANG_STATUS_OK);
    CHECK(findings.count >= 1 && items[0].kind == ROTLANG_FINDING_KIND_NAN && items[0].layers >= 1);
    CHECK(strcmp(rotlang_finding_code(items[0].kind), "orcaslicer::nan") == 0);
    for (size_t i = 0; i < 100; i++) CHECK(isfinite(angles[i]));
    STATUS(rotlang_template_free(nan), ROTLANG_STATUS_OK);

    /* Bytes that are not UTF-8: OrcaSlicer reads them as they are, and so does the
     * dialect through rotlang_parse_bytes (a lone 0xb0 reads like the UTF-8 degree
     * sign); the rotlang dialect refuses them. */
    RotlangTemplate *latin1 = NULL, *utf8 = NULL;
    STATUS(rotlang_parse_bytes("+30\xb0", 4, ROTLANG_TARGET_SPARSE, &latin1), ROTLANG_STATUS_OK);
    STATUS(rotlang_parse_bytes("+30\xc2\xb0", 5, ROTLANG_TARGET_SPARSE, &utf8), ROTLANG_STATUS_OK);
    double raw[3], degree[3];
    STATUS(rotlang_expand(latin1, &cube, &orca, 0, 3, raw, NULL, 3, NULL), ROTLANG_STATUS_OK);
    STATUS(rotlang_expand(utf8, &cube, &orca, 0, 3, degree, NULL, 3, NULL), ROTLANG_STATUS_OK);
    CHECK(raw[0] == 30 && raw[1] == 60 && raw[2] == 90);
    CHECK(degree[0] == 30 && degree[1] == 60 && degree[2] == 90);
    STATUS(rotlang_expand(latin1, &cube, NULL, 0, 3, raw, NULL, 3, NULL), ROTLANG_STATUS_INVALID_UTF8);
    RotlangDiagnostic d;
    STATUS(rotlang_template_diagnostic(latin1, 0, &d), ROTLANG_STATUS_OK);
    CHECK(d.severity == ROTLANG_SEVERITY_ERROR && d.start == 3 && d.end == 4); /* the 0xb0 byte */
    STATUS(rotlang_template_free(latin1), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(utf8), ROTLANG_STATUS_OK);

    /* Text rotlang rejects still has OrcaSlicer angles; random access equals the batch. */
    RotlangTemplate *bad = parse("+30°, X, 0x10*2, nan");
    int errors = 0;
    STATUS(rotlang_template_has_errors(bad, &errors), ROTLANG_STATUS_OK);
    CHECK(errors == 1);
    STATUS(rotlang_expand(bad, &cube, &orca, 0, ROTLANG_TO_TOP, angles, NULL, 100, &findings), ROTLANG_STATUS_OK);
    STATUS(rotlang_evaluator_new(bad, &cube, &orca, &e), ROTLANG_STATUS_OK);
    for (size_t k = 0; k < 200; k++) {
        size_t i = (k * 61) % 100;
        STATUS(rotlang_evaluator_layer(e, i, &layer), ROTLANG_STATUS_OK);
        CHECK(layer.angle == angles[i] && isfinite(layer.angle));
    }
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(bad), ROTLANG_STATUS_OK);

    /* `1:4`: a quarter turn for rotlang, 1 degree for OrcaSlicer (SEMANTICS 10.2). */
    RotlangTemplate *flip = parse("1:4");
    double mine[5];
    STATUS(rotlang_expand(flip, &cube, NULL, 0, 5, mine, NULL, 5, NULL), ROTLANG_STATUS_OK);
    STATUS(rotlang_expand(flip, &cube, &orca, 0, 5, angles, NULL, 5, &findings), ROTLANG_STATUS_OK);
    CHECK(findings.count == 0 && mine[4] == 90 && angles[4] == 1);
    STATUS(rotlang_template_free(flip), ROTLANG_STATUS_OK);
}

/* The seed of the random joints: the same seed gives the same angles, another seed other
 * angles, and layer-by-layer access agrees with the batch for a non-zero seed. */
static void seeded(void) {
    RotlangTemplate *t = parse("+30~5, -15~10, 45");
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0);
    RotlangOptions seven = {0, 7, ROTLANG_DIALECT_ROTLANG}, eight = {0, 8, ROTLANG_DIALECT_ROTLANG};
    double first[100], again[100], other[100];
    STATUS(rotlang_expand(t, &cube, &seven, 0, ROTLANG_TO_TOP, first, NULL, 100, NULL), ROTLANG_STATUS_OK);
    STATUS(rotlang_expand(t, &cube, &seven, 0, ROTLANG_TO_TOP, again, NULL, 100, NULL), ROTLANG_STATUS_OK);
    STATUS(rotlang_expand(t, &cube, &eight, 0, ROTLANG_TO_TOP, other, NULL, 100, NULL), ROTLANG_STATUS_OK);
    CHECK(memcmp(first, again, sizeof first) == 0);
    size_t differ = 0;
    for (size_t i = 0; i < 100; i++) differ += first[i] != other[i];
    CHECK(differ > 10);
    RotlangEvaluator *e = NULL;
    STATUS(rotlang_evaluator_new(t, &cube, &seven, &e), ROTLANG_STATUS_OK);
    for (size_t k = 0; k < 100; k++) {
        size_t i = (k * 37) % 100;
        RotlangLayer layer;
        STATUS(rotlang_evaluator_layer(e, i, &layer), ROTLANG_STATUS_OK);
        CHECK(layer.angle == first[i]);
    }
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(t), ROTLANG_STATUS_OK);
}

static void hostile(void) {
    RotlangTemplate *t = parse("+10, -10");
    RotlangTemplate *out = (RotlangTemplate *)1;
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0);
    double angles[100];
    size_t n = 0;

    /* NULL pointers. */
    STATUS(rotlang_parse(NULL, 3, 0, &out), ROTLANG_STATUS_NULL_POINTER);
    CHECK(out == NULL);
    STATUS(rotlang_parse("0", 1, 0, NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_expand(NULL, &cube, NULL, 0, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_expand(t, NULL, NULL, 0, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_expand(t, &cube, NULL, 0, 1, NULL, NULL, 1, NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_template_diagnostic_count(t, NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_template_free(NULL), ROTLANG_STATUS_NULL_POINTER);
    STATUS(rotlang_evaluator_free(NULL), ROTLANG_STATUS_NULL_POINTER);
    RotlangModel no_heights = rotlang_model_heights(NULL, 3, 0.2);
    no_heights.layers = 0; /* NULL heights means uniform: zero layers */
    STATUS(rotlang_model_layer_count(&no_heights, &n), ROTLANG_STATUS_INVALID_MODEL);

    /* The empty template (NULL with length 0 is allowed). */
    RotlangTemplate *empty = NULL;
    STATUS(rotlang_parse(NULL, 0, 0, &empty), ROTLANG_STATUS_OK);
    STATUS(rotlang_expand(empty, &cube, NULL, 0, ROTLANG_TO_TOP, angles, NULL, 100, NULL), ROTLANG_STATUS_OK);
    CHECK(angles[0] == 0 && angles[99] == 0);
    STATUS(rotlang_template_free(empty), ROTLANG_STATUS_OK);

    /* Non-UTF-8 and unknown enum values. */
    STATUS(rotlang_parse("+10\xff", 4, 0, &out), ROTLANG_STATUS_INVALID_UTF8);
    CHECK(out == NULL);
    STATUS(rotlang_parse("+10", 3, 7, &out), ROTLANG_STATUS_INVALID_ARGUMENT);
    RotlangOptions bad_dialect = {0, 0, 42};
    STATUS(rotlang_expand(t, &cube, &bad_dialect, 0, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_INVALID_ARGUMENT);
    RotlangOptions bad_base = {NAN, 0, 0};
    STATUS(rotlang_expand(t, &cube, &bad_base, 0, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_INVALID_ARGUMENT);
    char message[256];
    rotlang_last_error(message, sizeof message);
    CHECK(strstr(message, "an argument has a value the library cannot accept: `base` must be a finite number of degrees within \u00b11000000000, not NaN") == message);
    RotlangModel huge = rotlang_model_uniform(SIZE_MAX, 0.2, 0);
    STATUS(rotlang_model_layer_count(&huge, &n), ROTLANG_STATUS_INVALID_MODEL);
    rotlang_last_error(message, sizeof message);
    CHECK(strstr(message, "`layers` must be a whole number from 1 to 100000000, not 18446744073709551615") != NULL || SIZE_MAX != 18446744073709551615u);

    /* Bad models: empty, NaN, negative, zero heights; NaN layer height; zero layers. */
    double heights[3] = {0.2, 0.2, 0.2};
    RotlangModel m = rotlang_model_heights(heights, 0, 0.2);
    STATUS(rotlang_model_layer_count(&m, &n), ROTLANG_STATUS_INVALID_MODEL);
    m.heights_len = 3;
    STATUS(rotlang_model_layer_count(&m, &n), ROTLANG_STATUS_OK);
    CHECK(n == 3);
    heights[1] = NAN;
    STATUS(rotlang_expand(t, &m, NULL, 0, 3, angles, NULL, 3, NULL), ROTLANG_STATUS_INVALID_MODEL);
    char why[256];
    rotlang_last_error(why, sizeof why);
    CHECK(strstr(why, "layer 1") != NULL);
    heights[1] = -0.2;
    STATUS(rotlang_model_layer_count(&m, &n), ROTLANG_STATUS_INVALID_MODEL);
    heights[1] = 0;
    STATUS(rotlang_model_layer_count(&m, &n), ROTLANG_STATUS_INVALID_MODEL);
    heights[1] = 0.2;
    m.layer_height = NAN;
    STATUS(rotlang_model_layer_count(&m, &n), ROTLANG_STATUS_INVALID_MODEL);
    RotlangModel u = rotlang_model_uniform(0, 0.2, 0);
    STATUS(rotlang_model_layer_count(&u, &n), ROTLANG_STATUS_INVALID_MODEL);
    u = rotlang_model_uniform(10, 0.2, -1);
    STATUS(rotlang_model_layer_count(&u, &n), ROTLANG_STATUS_INVALID_MODEL);

    /* Ranges and buffers. */
    STATUS(rotlang_expand(t, &cube, NULL, 0, ROTLANG_TO_TOP, angles, NULL, 99, NULL), ROTLANG_STATUS_BUFFER_TOO_SMALL);
    STATUS(rotlang_expand(t, &cube, NULL, 100, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_OUT_OF_RANGE);
    STATUS(rotlang_expand(t, &cube, NULL, 90, 11, angles, NULL, 100, NULL), ROTLANG_STATUS_OUT_OF_RANGE);
    STATUS(rotlang_expand(t, &cube, NULL, 1, (size_t)-2, angles, NULL, 100, NULL), ROTLANG_STATUS_OUT_OF_RANGE);
    angles[0] = 123;
    STATUS(rotlang_expand(t, &cube, NULL, 0, 0, angles, NULL, 0, NULL), ROTLANG_STATUS_OK);
    CHECK(angles[0] == 123); /* an empty range writes nothing */

    /* Double free, foreign pointers, a handle of the other kind. */
    RotlangEvaluator *e = NULL;
    STATUS(rotlang_evaluator_new(t, &cube, NULL, &e), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free((RotlangTemplate *)e), ROTLANG_STATUS_INVALID_HANDLE);
    STATUS(rotlang_evaluator_free((RotlangEvaluator *)t), ROTLANG_STATUS_INVALID_HANDLE);
    STATUS(rotlang_template_free((RotlangTemplate *)angles), ROTLANG_STATUS_INVALID_HANDLE);
    STATUS(rotlang_template_diagnostic_count((RotlangTemplate *)0x1234, &n), ROTLANG_STATUS_INVALID_HANDLE);
    STATUS(rotlang_evaluator_free(e), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(t), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(t), ROTLANG_STATUS_INVALID_HANDLE);
    STATUS(rotlang_expand(t, &cube, NULL, 0, 1, angles, NULL, 1, NULL), ROTLANG_STATUS_INVALID_HANDLE);
}

/* One template, many threads, each expanding a different model and checking every layer
 * against the same expansion done up front on this thread. */
#define MAX_THREADS 16
#define MAX_LAYERS 5000
static size_t THREADS = 8, LAYERS = 5000; /* smaller under valgrind (argv) */
static RotlangTemplate *shared, *shared_orca;
static double reference[MAX_LAYERS], reference_orca[MAX_LAYERS];
/* Text rotlang rejects, read by the OrcaSlicer dialect with a seed. */
static const RotlangOptions ORCA = {0, 5, ROTLANG_DIALECT_ORCASLICER};

static void *worker(void *arg) {
    size_t id = (size_t)arg;
    double *angles = malloc(sizeof(double) * LAYERS);
    RotlangModel model = rotlang_model_uniform(LAYERS, 0.2, 0.3);
    RotlangEvaluator *e = NULL;
    size_t bad = 0;
    for (int round = 0; round < 4; round++) {
        if (rotlang_expand(shared, &model, NULL, 0, ROTLANG_TO_TOP, angles, NULL, LAYERS, NULL))
            bad++;
        for (size_t i = 0; i < LAYERS; i++) bad += angles[i] != reference[i];
    }
    if (rotlang_evaluator_new(shared, &model, NULL, &e)) bad++;
    for (size_t k = 0; k < LAYERS; k++) {
        size_t i = (k * 7919 + id * 131) % LAYERS;
        RotlangLayer layer;
        if (rotlang_evaluator_layer(e, i, &layer) || layer.angle != reference[i]) bad++;
    }
    if (rotlang_evaluator_free(e)) bad++;
    /* The OrcaSlicer-dialect template, shared the same way. */
    for (int round = 0; round < 2; round++) {
        if (rotlang_expand(shared_orca, &model, &ORCA, 0, ROTLANG_TO_TOP, angles, NULL, LAYERS, NULL)) bad++;
        for (size_t i = 0; i < LAYERS; i++) bad += angles[i] != reference_orca[i];
    }
    if (rotlang_evaluator_new(shared_orca, &model, &ORCA, &e)) bad++;
    for (size_t k = 0; k < LAYERS; k += 1 + LAYERS / 200) { /* forward and back: reopens */
        size_t i = (k * 7919 + id * 131) % LAYERS;
        RotlangLayer layer;
        if (rotlang_evaluator_layer(e, i, &layer) || layer.angle != reference_orca[i]) bad++;
    }
    if (rotlang_evaluator_free(e)) bad++;
    free(angles);
    return (void *)bad;
}

static void threads(void) {
    shared = parse("5, 10!, +20, +10L25%, -10~50, #3, +45Z10mm");
    RotlangModel model = rotlang_model_uniform(LAYERS, 0.2, 0.3);
    STATUS(rotlang_expand(shared, &model, NULL, 0, ROTLANG_TO_TOP, reference, NULL, LAYERS, NULL),
           ROTLANG_STATUS_OK);
    shared_orca = parse("+30\xc2\xb0, X, -15/10%, 0x10*2, +5~3");
    STATUS(rotlang_expand(shared_orca, &model, &ORCA, 0, ROTLANG_TO_TOP, reference_orca, NULL, LAYERS, NULL),
           ROTLANG_STATUS_OK);
    pthread_t tid[MAX_THREADS];
    for (size_t i = 0; i < THREADS; i++) CHECK(pthread_create(&tid[i], NULL, worker, (void *)i) == 0);
    for (size_t i = 0; i < THREADS; i++) {
        void *bad = NULL;
        CHECK(pthread_join(tid[i], &bad) == 0);
        CHECK(bad == NULL);
    }
    STATUS(rotlang_template_free(shared), ROTLANG_STATUS_OK);
    STATUS(rotlang_template_free(shared_orca), ROTLANG_STATUS_OK);
}

/* Freeing a template while other threads evaluate it: each call either finishes on the
 * template (it holds its own reference) or, once the free went through, is refused with
 * INVALID_HANDLE. Never a crash or a read of freed memory. */
static RotlangTemplate *doomed;

static void *racer(void *arg) {
    (void)arg;
    RotlangModel model = rotlang_model_uniform(2000, 0.2, 0);
    double *angles = malloc(sizeof(double) * 2000);
    size_t unexpected = 0, refused = 0;
    for (int round = 0; round < 400 && refused < 3; round++) {
        RotlangStatus s = rotlang_expand(doomed, &model, NULL, 0, ROTLANG_TO_TOP, angles, NULL, 2000, NULL);
        if (s == ROTLANG_STATUS_INVALID_HANDLE) refused++;
        else if (s != ROTLANG_STATUS_OK || angles[1999] != angles[1999 % 2]) unexpected++;
    }
    free(angles);
    return (void *)unexpected;
}

static void free_while_evaluating(void) {
    doomed = parse("0, 90");
    pthread_t tid[3];
    for (size_t i = 0; i < 3; i++) CHECK(pthread_create(&tid[i], NULL, racer, NULL) == 0);
    STATUS(rotlang_template_free(doomed), ROTLANG_STATUS_OK);
    for (size_t i = 0; i < 3; i++) {
        void *unexpected = NULL;
        CHECK(pthread_join(tid[i], &unexpected) == 0);
        CHECK(unexpected == NULL);
    }
}

/* Arguments (optional): layers per thread, threads. */
int main(int argc, char **argv) {
    if (argc > 2) {
        LAYERS = (size_t)atoi(argv[1]);
        THREADS = (size_t)atoi(argv[2]);
        if (LAYERS < 1 || LAYERS > MAX_LAYERS || THREADS < 1 || THREADS > MAX_THREADS) return 2;
    }
    versions();
    evaluates();
    diagnostics();
    orcaslicer();
    seeded();
    hostile();
    threads();
    free_while_evaluating();
    /* Every handle made was freed (valgrind counts the registry as still reachable). */
    CHECK(rotlang_live_handles() == 0);
    if (failures) {
        fprintf(stderr, "%d of %d checks failed\n", failures, checks);
        return 1;
    }
    printf("ok %d checks\n", checks);
    return 0;
}
