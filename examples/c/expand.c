/* Parse a template, report its diagnostics, print every layer's angle on a 20 mm cube.
 * Build: cc -Iinclude examples/c/expand.c target/release/librotlang_capi.a -lpthread -ldl -lm */
#include <stdio.h>
#include <string.h>
#include "rotlang.h"

int main(int argc, char **argv) {
    const char *text = argc > 1 ? argv[1] : "+10L25%, -10l25%";
    RotlangTemplate *tpl = NULL;
    if (rotlang_parse(text, strlen(text), ROTLANG_TARGET_SPARSE, &tpl) != ROTLANG_STATUS_OK) {
        char why[256];
        rotlang_last_error(why, sizeof why);
        fprintf(stderr, "rotlang: %s\n", why);
        return 2;
    }
    size_t count = 0;
    rotlang_template_diagnostic_count(tpl, &count);
    for (size_t i = 0; i < count; i++) {
        RotlangDiagnostic d;
        rotlang_template_diagnostic(tpl, i, &d);
        fprintf(stderr, "%s[%s] bytes %zu..%zu: %s\n",
                d.severity == ROTLANG_SEVERITY_ERROR ? "error" : "warning", d.code, d.start, d.end,
                d.message);
    }
    RotlangModel cube = rotlang_model_uniform(100, 0.2, 0.0); /* 100 layers of 0.2 mm */
    double angles[100];
    RotlangStatus status = rotlang_expand(tpl, &cube, NULL, 0, ROTLANG_TO_TOP, angles, NULL, 100, NULL);
    if (status == ROTLANG_STATUS_OK)
        for (size_t i = 0; i < 100; i++) printf("%zu %.6f\n", i, angles[i]);
    else
        fprintf(stderr, "rotlang: %s\n", rotlang_status_message(status));
    rotlang_template_free(tpl);
    if (rotlang_live_handles() != 0) { /* a forgotten free: valgrind cannot see it */
        fprintf(stderr, "rotlang: %zu handles not freed\n", rotlang_live_handles());
        return 3;
    }
    return status == ROTLANG_STATUS_OK ? 0 : 1;
}
