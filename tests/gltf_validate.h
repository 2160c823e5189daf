/* SPDX-License-Identifier: MIT */
/* tests/gltf_validate.py (the glTF 2.0 specification's MUST rules, python3's standard
 * library) on the .glb files the tests write. Include after <cmocka.h> and tmpdir.h. */
#ifndef RAD_TESTS_GLTF_VALIDATE_H
#define RAD_TESTS_GLTF_VALIDATE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs the validator on the N files PATHS; its report into tmp_path("validate.txt"). The
   exit status, or -1 when python3 is missing (said: the check is skipped). */
static inline int gltf_validator(const char *const *paths, int n)
{
    char cmd[8192];
    size_t at;
    int rc, i;
    if (system("command -v python3 >/dev/null 2>&1") != 0) {
        print_message("python3 not installed: the glTF validator skipped\n");
        return -1;
    }
    at = (size_t)snprintf(cmd, sizeof cmd, "python3 tests/gltf_validate.py");
    for (i = 0; i < n && at < sizeof cmd; i++)
        at += (size_t)snprintf(cmd + at, sizeof cmd - at, " '%s'", paths[i]);
    if (at < sizeof cmd)
        snprintf(cmd + at, sizeof cmd - at, " > '%s' 2>&1", tmp_path("validate.txt"));
    assert_true(at < sizeof cmd);
    rc = system(cmd);
    return rc == -1 ? -1 : WIFEXITED(rc) ? WEXITSTATUS(rc) : 128;
}

/* PATH breaks none of the rules (their report printed when it does). */
static inline void gltf_validates(const char *path)
{
    char cmd[600];
    int rc = gltf_validator(&path, 1);
    if (rc > 0) {
        snprintf(cmd, sizeof cmd, "cat '%s' >&2", tmp_path("validate.txt"));
        if (system(cmd)) {}
    }
    assert_true(rc <= 0);
}

/* Each of the N files PATHS is refused, a line of the report naming it and WHAT[i]
   (one run of the validator for them all). */
static inline void gltf_refused(const char *const *paths, const char *const *what, int n)
{
    static char text[65536];
    FILE *f;
    size_t len;
    int rc = gltf_validator(paths, n), i;
    if (rc < 0) return;
    f = fopen(tmp_path("validate.txt"), "rb");
    assert_non_null(f);
    len = fread(text, 1, sizeof text - 1, f);
    text[len] = '\0';
    fclose(f);
    assert_int_equal(rc, 1);
    for (i = 0; i < n; i++) {
        const char *line = text;
        int found = 0;
        while (line && *line && !found) {
            const char *end = strchr(line, '\n');
            size_t ll = end ? (size_t)(end - line) : strlen(line), pl = strlen(paths[i]);
            char one[1024];
            snprintf(one, sizeof one, "%.*s", (int)ll, line);
            found =
                !strncmp(one, paths[i], pl) && one[pl] == ':' && strstr(one + pl, what[i]) != NULL;
            if (found) print_message("refused: %s\n", one);
            line = end ? end + 1 : NULL;
        }
        if (!found)
            fail_msg("the validator did not refuse %s for '%s':\n%s", paths[i], what[i], text);
    }
}

#endif
