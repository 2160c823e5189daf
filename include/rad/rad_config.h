/* rad — compile-time configuration.
 *
 * Every limit has an #ifndef default; override on the command line (-DRAD_...=N) or
 * collect overrides in a file of your own and build with -DRAD_CONFIG_FILE='"myconf.h"'.
 * Runtime choices (mesh sizes, hemi-cube resolution) live in rad_config_t (rad.h).
 */
#ifndef RAD_CONFIG_H
#define RAD_CONFIG_H

#ifdef RAD_CONFIG_FILE
#include RAD_CONFIG_FILE
#endif
/* Installed headers: the values the library was built with (rad_build.h). */
#include "rad_build.h"

/* 1 builds the float twin: the same algorithm with float scalars (tests, comparisons). */
#ifndef RAD_FLOAT
#define RAD_FLOAT 0
#endif

/* Width of element, vertex, patch and surface indices: 16 saves RAM on small targets
 * (at most 65534 of each), 32 lifts the limit to 2^32 - 2. Results do not depend on it. */
#ifndef RAD_INDEX_BITS
#define RAD_INDEX_BITS 32
#endif
#if RAD_INDEX_BITS != 16 && RAD_INDEX_BITS != 32
#error "RAD_INDEX_BITS must be 16 or 32"
#endif

/* Largest hemi-cube resolution (pixels along the top face's edge; must be even). It
 * bounds the delta form factor table and keeps the rasterizer's integer maths in range. */
#ifndef RAD_MAX_RES
#define RAD_MAX_RES 1024
#endif
#if RAD_MAX_RES < 8 || RAD_MAX_RES > 2048 || (RAD_MAX_RES % 2) != 0
#error "RAD_MAX_RES must be even and within 8..2048"
#endif

/* Largest raster (view or hemi-cube face) in pixels along either axis. 2048 keeps every
 * edge function and plane gradient of the rasterizer inside int64 (see lib/raster.c). */
#ifndef RAD_MAX_RASTER
#define RAD_MAX_RASTER 2048
#endif
#if RAD_MAX_RASTER > 2048 || RAD_MAX_RASTER < RAD_MAX_RES
#error "RAD_MAX_RASTER must be within RAD_MAX_RES..2048"
#endif

#endif
