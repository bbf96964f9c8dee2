/* eventlog.c - lcm-logger event logs into the monitor core (eventlog.h):
 * LCM's event-log API reads the events, this file tells a corrupted region
 * from the end of the log, and counts.
 *
 * lcm_eventlog_read_next_event() returns NULL both at the end of the file
 * and on a bad header; a bad header is told from the end by feof(), and
 * the next call resynchronises on the next sync word.  A length field that
 * points past the end of the file looks like the end too: when bytes are
 * left after the last good event, the reader rewinds to just after the
 * failed sync word and scans on, so one corrupted length cannot hide the
 * rest of the log. */
#include "eventlog.h"

#include <errno.h>
#include <lcm/eventlog.h>
#include <regex.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "monitor.h"
#include "swaywatch/status.h"

struct sw_lcmlog {
    lcm_eventlog_t *log;
    off_t size; /* bytes in the file, to tell its end from a bad length */
    regex_t channel;
    int strict;
    sw_lcmlog_counts_t c;
};

/* LCM anchors channel regexes at both ends. */
static int compile_channel(const char *arg, regex_t *re)
{
    size_t len = strlen(arg);
    char *anchored = malloc(len + 5);
    if (!anchored)
        return SW_ENOMEM;
    snprintf(anchored, len + 5, "^(%s)$", arg);
    int r = regcomp(re, anchored, REG_EXTENDED | REG_NOSUB);
    free(anchored);
    return r == 0 ? SW_OK : r == REG_ESPACE ? SW_ENOMEM : SW_EINVAL;
}

sw_lcmlog_t *sw_lcmlog_open(const char *path, const sw_lcmlog_opts_t *o, int *err)
{
    const sw_lcmlog_opts_t none = {0};
    if (!o)
        o = &none;
    sw_lcmlog_t *l = calloc(1, sizeof *l);
    if (!l) {
        *err = SW_ENOMEM;
        return NULL;
    }
    *err = compile_channel(o->channel ? o->channel : SW_MON_ACCEL_CHANNEL, &l->channel);
    if (*err != SW_OK) {
        free(l);
        return NULL;
    }
    l->strict = o->strict;
    struct stat st;
    l->log = lcm_eventlog_create(path, "r");
    if (!l->log || fstat(fileno(l->log->f), &st) != 0) {
        int saved = errno;
        sw_lcmlog_close(l);
        errno = saved;
        *err = SW_ENOTFOUND;
        return NULL;
    }
    l->size = st.st_size;
    return l;
}

void sw_lcmlog_close(sw_lcmlog_t *l)
{
    if (!l)
        return;
    if (l->log)
        lcm_eventlog_destroy(l->log);
    regfree(&l->channel);
    free(l);
}

void sw_lcmlog_counts(const sw_lcmlog_t *l, sw_lcmlog_counts_t *c)
{
    *c = l->c;
}

/* Big-endian uint32 at the current position (no advance); 0 if none. */
static uint32_t peek_sync(FILE *f, off_t at)
{
    unsigned char b[4];
    if (fseeko(f, at, SEEK_SET) != 0 || fread(b, 1, 4, f) != 4)
        return 0;
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* After a NULL at end of file with bytes left from `from`: position the
 * log just past the first sync word at or after `from`, so scanning goes
 * on behind it.  Returns 0 if there is one, -1 if the rest is junk. */
static int skip_bad_sync(FILE *f, off_t from, off_t size)
{
    clearerr(f);
    for (off_t at = from; at + 4 <= size; at++)
        if (peek_sync(f, at) == SW_LCMLOG_SYNC)
            return fseeko(f, at + 1, SEEK_SET) == 0 ? 0 : -1;
    return -1;
}

/* A corrupted region is a stretch of bytes between two good events; each
 * is counted once however many reads it takes to get past it. */
int sw_lcmlog_read(sw_lcmlog_t *l, sw_mon_t *mon)
{
    FILE *f = l->log->f;
    int in_bad = 0;
    for (;;) {
        off_t at = ftello(f);
        lcm_eventlog_event_t *ev = lcm_eventlog_read_next_event(l->log);
        if (!ev) {
            int eof = feof(f);
            /* Clean end: nothing left after the last event. */
            if (eof && at >= l->size)
                break;
            if (!in_bad)
                l->c.corrupt++;
            in_bad = 1;
            if (l->strict)
                return SW_EPARSE;
            /* Not at the end: a bad header, and the next call resynchronises.
             * At the end with bytes left: a truncated last event, or a length
             * pointing past the end; scan on behind its sync word. */
            if (eof && skip_bad_sync(f, at, l->size) != 0)
                break;
            continue;
        }
        in_bad = 0;
        l->c.events++;
        if (regexec(&l->channel, ev->channel, 0, NULL, 0) != 0) {
            l->c.other_channels++;
            lcm_eventlog_free_event(ev);
            continue;
        }
        l->c.on_channel++;
        sw_mon_feed(mon, ev->data, (size_t)ev->datalen, ev->timestamp,
                    (double)ev->timestamp / 1e6, NULL);
        lcm_eventlog_free_event(ev);
        if (l->strict) { /* a refusal, of this sample or of one held before it */
            sw_mon_counts_t k;
            sw_mon_counts(mon, &k);
            if (sw_mon_rejected(&k) > 0)
                return SW_EINVAL;
        }
    }
    return SW_OK;
}
