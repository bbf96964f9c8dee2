/* SPDX-License-Identifier: GPL-3.0-or-later */
/* status.h - signed status codes shared by every swaywatch call.
 *
 * 0 is success, > 0 reports that something happened (an event), < 0 is an
 * error.  sw_strerror() turns any of them into a short English phrase.  The
 * library never prints: calls that can fail in more than one way also fill
 * a caller-supplied message buffer with the details. */
#ifndef SWAYWATCH_STATUS_H
#define SWAYWATCH_STATUS_H

#include "export.h"

#ifdef __cplusplus
extern "C" {
#endif

enum {
    SW_OK = 0,
    SW_EVENT = 1,         /* the call completed and reported at least one event */
    SW_EINVAL = -1,       /* invalid argument or invalid value in a scene */
    SW_ENOMEM = -2,       /* allocation failed */
    SW_EORDER = -3,       /* sample time not after the previous one (at the resolution
                             of the time relative to the first sample) */
    SW_ENONFINITE = -4,   /* non-finite input value */
    SW_EUNSTABLE = -5,    /* the forced step violates the scheme's stability bound */
    SW_EFAULT = -6,       /* model fault: state became non-finite or left the model */
    SW_EGSL = -7,         /* a GSL routine failed */
    SW_EPARSE = -8,       /* malformed text (scene file, CSV row) */
    SW_ENOTFOUND = -9,    /* no such name (scheme, column, key) */
    SW_ETOOBIG = -10,     /* input exceeds a documented limit */
    SW_EAMBIGUOUS = -11,  /* the input does not say what it holds (which column is which, in
                             what unit): the caller must say it */
    SW_ERESOLUTION = -12, /* a time so large that its resolution is not far finer than the
                             samples' spacing (|t| >= 2^33 s, steps above 2e-6 s): most
                             often a time unit mistake */
    SW_EAUTH = -13        /* not authentic: no MAC, a MAC that does not match, or a copy
                             of an earlier message (authenticated sensors) */
};

/* A constant string describing code; never NULL. */
SW_API const char *sw_strerror(int code);

#ifdef __cplusplus
}
#endif
#endif
