/* SPDX-License-Identifier: MIT */
/* assimp (Debian assimp-utils) as a real consumer of the exported files: `assimp info`
 * must read them with no error. Include after <cmocka.h> and tmpdir.h. */
#ifndef RAD_TESTS_ASSIMP_H
#define RAD_TESTS_ASSIMP_H

#include <stdio.h>
#include <stdlib.h>

/* assimp reads FILE without an error (skipped with a message if not installed). */
static inline void assimp_reads(const char *path)
{
    char cmd[600];
    int rc;
    if (system("command -v assimp >/dev/null 2>&1") != 0) {
        print_message("assimp not installed (Debian assimp-utils): its check skipped\n");
        return;
    }
    snprintf(cmd, sizeof cmd, "assimp info '%s' > '%s' 2>&1", path, tmp_path("assimp.txt"));
    rc = system(cmd);
    if (rc != 0) {
        snprintf(cmd, sizeof cmd, "cat '%s' >&2", tmp_path("assimp.txt"));
        if (system(cmd)) {}
    }
    assert_int_equal(rc, 0);
}

#endif
