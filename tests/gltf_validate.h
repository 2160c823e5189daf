/* SPDX-License-Identifier: MIT */
/* tests/gltf_validate.py (the glTF 2.0 specification's MUST rules, python3's standard
 * library) on the .glb files the tests write. Include after <cmocka.h> and tmpdir.h. */
#ifndef RAD_TESTS_GLTF_VALIDATE_H
#define RAD_TESTS_GLTF_VALIDATE_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

/* Runs the validator on PATH; its report into tmp_path("validate.txt"). The exit
   status, or -1 when python3 is missing (said once a call: the check is skipped). */
static inline int gltf_validator(const char *path)
{
    char cmd[1200];
    int rc;
    if (system("command -v python3 >/dev/null 2>&1") != 0) {
        print_message("python3 not installed: the glTF validator skipped\n");
        return -1;
    }
    snprintf(cmd, sizeof cmd, "python3 tests/gltf_validate.py '%s' > '%s' 2>&1", path, tmp_path("validate.txt"));
    rc = system(cmd);
    return rc == -1 ? -1 : WIFEXITED(rc) ? WEXITSTATUS(rc) : 128;
}

/* PATH breaks none of the rules (their report printed when it does). */
static inline void gltf_validates(const char *path)
{
    char cmd[600];
    int rc = gltf_validator(path);
    if (rc > 0) {
        snprintf(cmd, sizeof cmd, "cat '%s' >&2", tmp_path("validate.txt"));
        if (system(cmd)) {
        }
    }
    assert_true(rc <= 0);
}

/* PATH is refused, the report naming WHAT. */
static inline void gltf_refused(const char *path, const char *what)
{
    FILE *f;
    char text[4096] = "";
    size_t n;
    int rc = gltf_validator(path);
    if (rc < 0)
        return;
    f = fopen(tmp_path("validate.txt"), "rb");
    assert_non_null(f);
    n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    print_message("validator on a broken file (exit %d): %s", rc, text);
    assert_int_equal(rc, 1);
    if (!strstr(text, what))
        fail_msg("the validator's report does not name '%s'", what);
}

#endif
