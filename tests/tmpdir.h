/* SPDX-License-Identifier: MIT */
/* The temporary directory of a test program that writes files: made by tmpdir_make in
 * its group setup, removed with everything in it by tmpdir_remove in its teardown. */
#ifndef RAD_TESTS_TMPDIR_H
#define RAD_TESTS_TMPDIR_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char tmpdir[64];

/* A path in the temporary directory (NAME cut at 200 characters). Up to 32 results
 * stay valid at once. */
static inline const char *tmp_path(const char *name)
{
    static char ring[32][320];
    static int next;
    char *p = ring[next++ % 32];
    snprintf(p, sizeof ring[0], "%s/%.200s", tmpdir, name);
    return p;
}

static inline void remove_tree(const char *path)
{
    DIR *d = opendir(path);
    struct dirent *de;
    char p[600];
    if (!d) {
        unlink(path);
        return;
    }
    while ((de = readdir(d)) != NULL) {
        if (!strcmp(de->d_name, ".") || !strcmp(de->d_name, "..")) continue;
        snprintf(p, sizeof p, "%.300s/%.255s", path, de->d_name); /* the tests nest shallowly */
        remove_tree(p);
    }
    closedir(d);
    rmdir(path);
}

/* /tmp/rad_test_PROG.XXXXXX; 0, or -1 with the reason on stderr. */
static inline int tmpdir_make(const char *prog)
{
    snprintf(tmpdir, sizeof tmpdir, "/tmp/rad_test_%.20s.XXXXXX", prog);
    if (mkdtemp(tmpdir)) return 0;
    perror("mkdtemp");
    return -1;
}

static inline void tmpdir_remove(void)
{
    remove_tree(tmpdir);
}

/* The CMocka group setup and teardown of a test program named PROG. */
#define TMPDIR_GROUP(prog)                  \
    static int group_setup(void **state)    \
    {                                       \
        (void)state;                        \
        return tmpdir_make(prog);           \
    }                                       \
    static int group_teardown(void **state) \
    {                                       \
        (void)state;                        \
        tmpdir_remove();                    \
        return 0;                           \
    }

#endif
