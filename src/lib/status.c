/* SPDX-License-Identifier: GPL-3.0-or-later */
/* status.c - text for the status codes of status.h. */
#include "swaywatch/status.h"

const char *sw_strerror(int code)
{
    switch (code) {
        case SW_OK: return "success";
        case SW_EVENT: return "event reported";
        case SW_EINVAL: return "invalid argument or value";
        case SW_ENOMEM: return "out of memory";
        case SW_EORDER: return "time not increasing";
        case SW_ENONFINITE: return "non-finite value";
        case SW_EUNSTABLE: return "time step above the scheme's stability bound";
        case SW_EFAULT: return "model fault";
        case SW_EGSL: return "GSL routine failed";
        case SW_EPARSE: return "malformed input";
        case SW_ENOTFOUND: return "no such name";
        case SW_ETOOBIG: return "input exceeds a limit";
        case SW_EAMBIGUOUS: return "the input does not say what it holds";
        case SW_ERESOLUTION: return "time too large for its resolution (a time unit mistake?)";
        case SW_EAUTH: return "not authentic (no MAC, a wrong MAC, or a replayed message)";
        default: return code > 0 ? "event reported" : "unknown error";
    }
}
