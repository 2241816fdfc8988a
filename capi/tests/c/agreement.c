/* The C side of the bindings' agreement table (bindings/agreement/cases.json): one case
 * a line on stdin, written by capi/tests/agreement.rs, as
 *   dialect target kind layers layer_height first_layer_height bottom top base seed
 *   count heights... template
 * (kind 0: no model, so the 20 mm cube; 1: uniform; 2: a list of heights). For each, one
 * line on stdout: "ok" and every angle, or "err", the status and rotlang_last_error's
 * detail (the message without the status's own text). With an argument, the cases are
 * read from that file instead (for valgrind, which the test runs it under too). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rotlang.h"

enum { MAX_HEIGHTS = 64, MAX_ANGLES = 256 };

static void fail(RotlangStatus status) {
    char message[512];
    rotlang_last_error(message, sizeof message);
    const char *text = rotlang_status_message((uint32_t)status);
    size_t skip = strlen(text);
    const char *detail = message;
    if (strncmp(message, text, skip) == 0 && strncmp(message + skip, ": ", 2) == 0) {
        detail = message + skip + 2;
    }
    printf("err %d %s\n", (int)status, detail);
}

int main(int argc, char **argv) {
    static char line[1 << 16];
    if (argc > 1 && !freopen(argv[1], "r", stdin)) {
        perror(argv[1]);
        return 2;
    }
    while (fgets(line, sizeof line, stdin)) {
        char *p = line;
        unsigned dialect = (unsigned)strtoul(p, &p, 10);
        unsigned target = (unsigned)strtoul(p, &p, 10);
        int kind = (int)strtol(p, &p, 10);
        size_t layers = (size_t)strtoull(p, &p, 10);
        double layer_height = strtod(p, &p);
        double first = strtod(p, &p);
        uint32_t bottom = (uint32_t)strtoul(p, &p, 10);
        uint32_t top = (uint32_t)strtoul(p, &p, 10);
        double base = strtod(p, &p);
        uint64_t seed = (uint64_t)strtoull(p, &p, 10);
        size_t count = (size_t)strtoull(p, &p, 10);
        double heights[MAX_HEIGHTS];
        for (size_t i = 0; i < count && i < MAX_HEIGHTS; i++) {
            heights[i] = strtod(p, &p);
        }
        if (*p == ' ') p++;
        p[strcspn(p, "\n")] = '\0';

        RotlangModel model;
        if (kind == 2) {
            model = rotlang_model_heights(heights, count, layer_height);
        } else if (kind == 1) {
            model = rotlang_model_uniform(layers, layer_height, first);
        } else {
            model = rotlang_model_uniform(100, 0.2, 0);
        }
        model.bottom_shells = bottom;
        model.top_shells = top;
        RotlangOptions options = {base, seed, dialect};

        RotlangTemplate *template_ = NULL;
        RotlangStatus status = rotlang_parse(p, strlen(p), target, &template_);
        if (status != ROTLANG_STATUS_OK) {
            fail(status);
            continue;
        }
        double angles[MAX_ANGLES];
        size_t n = 0;
        status = rotlang_model_layer_count(&model, &n);
        if (status == ROTLANG_STATUS_OK && n > MAX_ANGLES) {
            printf("err -1 the table's models have at most %d layers\n", MAX_ANGLES);
        } else if (status == ROTLANG_STATUS_OK) {
            status = rotlang_expand(template_, &model, &options, 0, ROTLANG_TO_TOP, angles, NULL, MAX_ANGLES, NULL);
        }
        if (status != ROTLANG_STATUS_OK) {
            fail(status);
        } else if (n <= MAX_ANGLES) {
            printf("ok");
            for (size_t i = 0; i < n; i++) printf(" %.17g", angles[i]);
            printf("\n");
        }
        rotlang_template_free(template_);
    }
    return 0;
}
