/* SPDX-License-Identifier: MIT */
/* defaults — rad_cli's program defaults, one home: the options, the --help text and
 * rad_bench (which measures them) all read them here. The core's own defaults
 * (rad_config_t, rad_light_t) are in include/rad/rad.h (RAD_DEFAULT_*).
 *
 * Hemi-cube: every shot at DEF_RES once the unshot fraction is above DEF_COARSE, then
 * coarse shots down to DEF_COARSE_FLOOR(res): res / 8 made even, but not below 24 (a cube
 * of 8 or 16 misses whole surfaces), so that a res of 24 or less never coarsens. Stored
 * rows are every patch's row at res and never coarse: DEF_ROWS_RES and no coarse shots.
 * docs on the choice: docs/library.md, "Coarse shots". */
#ifndef RAD_TOOLS_DEFAULTS_H
#define RAD_TOOLS_DEFAULTS_H

#define DEF_RES               192
#define DEF_COARSE            1.0
#define DEF_ROWS_RES          128
#define DEF_COARSE_FLOOR(res) ((res) / 16 * 2 >= 24 ? (res) / 16 * 2 : (res) < 24 ? (res) : 24)

/* The gather resolution of --lightmap's texels and the probes without --gather, chosen
 * by the texels' error against resolution 256 (rad_bench --gather-res; docs/cli.md):
 * the lowest of 16, 32, 48, 64 within 2% rms on a room with cornices and on
 * CornellBox-Original (32: 1.9% and 4.4%, its worst texels 9% and 24% off: the
 * streaks under cornices), at about twice the time of a gather at 32. */
#define DEF_GATHER_RES        64
/* rad_cli notes --lightmap-soft elements when a gathered lightmap's first pass says
 * that the passes left may take longer than this (seconds): a level's gathers take tens
 * of minutes where its painted light takes seconds (docs/cli.md). */
#define LIGHTMAP_NOTE_SECONDS 300.0
/* The lightmap atlas' side in texels, and the image's width and height. */
#define DEF_LIGHTMAP_SIZE     512
#define DEF_IMAGE_SIZE        512

/* Shots a batch (rad_batch_begin; rad_cli --batch): chosen by measurement, rad_bench's
 * batch table and docs/new-batch.md. */
#define DEF_BATCH 4

/* A default written into help text: DEF_STR(DEF_RES) is "192". */
#define DEF_STR_(x) #x
#define DEF_STR(x)  DEF_STR_(x)

#endif
