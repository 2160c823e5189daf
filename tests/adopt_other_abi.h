/* What tests/adopt_other_abi.c (compiled with the other RAD_INDEX_BITS) reports. */
#ifndef ADOPT_OTHER_ABI_H
#define ADOPT_OTHER_ABI_H

typedef struct {
    unsigned index_bytes; /* sizeof(rad_index_t) in that unit */
    int scene_untouched;  /* its rad_scene_t still all 0xA5 after rad_init */
    int work_untouched;   /* its work buffer still all 0x5A */
} adopt_other_t;

/* Calls rad_init on that unit's pools; returns what rad_init returned. */
int adopt_other_init(adopt_other_t *out);

#endif
