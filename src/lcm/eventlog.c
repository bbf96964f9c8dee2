/* SPDX-License-Identifier: GPL-3.0-or-later */
/* eventlog.c - lcm-logger event logs read event by event (eventlog.h): a
 * reader of its own, which checks every header before it reads what the
 * header points at, resynchronises on the next sync word in one forward
 * scan, counts, and yields the events of the accel channel.
 *
 * LCM's reader (lcm_eventlog_read_next_event) is not used: it allocates
 * and reads whatever a header's lengths say (a length of 0x7fffffff
 * crashed it), reads to the end of the file at every length that points
 * past it (quadratic in the number of such headers), and prints.
 *
 * The log is read through a window of WIN bytes with pread(): the scan
 * position only goes forward, so each byte enters the window once; what
 * lies outside it is read directly, a bounded number of bytes per
 * candidate event (its sync word after the data, the part of an accel
 * event handed on).  A log that cannot seek is copied to an
 * unlinked temporary file first. */
#include "eventlog.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <regex.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "swaywatch/status.h"

#define WIN (64 * 1024) /* bytes of the read window; > header + longest channel */

typedef struct {
    long long start; /* offset of its sync word */
    long long data;  /* offset of its data */
    long long end;   /* offset after it */
    int32_t datalen;
    int64_t timestamp;
    char channel[SW_LCMLOG_MAX_CHANNEL + 1];
} event_t;

struct sw_lcmlog {
    int fd;
    long long size;
    regex_t channel;
    int has_re;
    sw_lcmlog_opts_t o;
    sw_lcmlog_counts_t c;
    int have_ts0;
    int64_t ts0;        /* us, the first accel event's receive time: arrival times are
                           fed relative to it, exactly */
    unsigned char *win; /* bytes [wbase, wbase + wlen) of the log */
    long long wbase;
    size_t wlen;
    int ioerr; /* errno of a failed read; 0: none */
    /* where sw_lcmlog_next() is: the next event's offset, and the
     * corrupted region it is in (in_bad) */
    long long pos;
    int in_bad;
    sw_lcmlog_region_t region;
    event_t cur; /* the event checked last: the channel of the one handed out */
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

static uint32_t get32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static int64_t get64(const unsigned char *p)
{
    return (int64_t)((uint64_t)get32(p) << 32 | get32(p + 4));
}

/* ---- opening ------------------------------------------------------------------- */

static sw_lcmlog_t *create(const sw_lcmlog_opts_t *o, int *err)
{
    const sw_lcmlog_opts_t none = {0};
    sw_lcmlog_t *l = calloc(1, sizeof *l);
    if (!l) {
        *err = SW_ENOMEM;
        return NULL;
    }
    l->fd = -1;
    l->o = o ? *o : none;
    if (l->o.spool_max <= 0)
        l->o.spool_max = SW_LCMLOG_SPOOL_MAX;
    l->c.first_corrupt = -1;
    *err = compile_channel(l->o.channel ? l->o.channel : SW_LCMLOG_CHANNEL, &l->channel);
    if (*err != SW_OK) {
        free(l);
        return NULL;
    }
    l->has_re = 1;
    l->win = malloc(WIN);
    if (!l->win) {
        sw_lcmlog_close(l);
        *err = SW_ENOMEM;
        return NULL;
    }
    return l;
}

static int write_all(int fd, const void *buf, size_t len)
{
    const char *p = buf;
    while (len > 0) {
        ssize_t w = write(fd, p, len);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0)
            return -1;
        p += w;
        len -= (size_t)w;
    }
    return 0;
}

/* Copy head, then the rest of in, to an unlinked temporary file: l->fd. */
static int spool(sw_lcmlog_t *l, FILE *in, const void *head, size_t len)
{
    const char *dir = getenv("TMPDIR");
    if (!dir || !dir[0])
        dir = "/tmp";
    size_t n = strlen(dir) + sizeof "/swaywatch-lcmlog-XXXXXX";
    char *path = malloc(n);
    if (!path)
        return SW_ENOMEM;
    snprintf(path, n, "%s/swaywatch-lcmlog-XXXXXX", dir);
    l->fd = mkstemp(path);
    if (l->fd >= 0)
        unlink(path); /* gone when closed, whatever happens */
    free(path);
    if (l->fd < 0)
        return SW_ENOTFOUND;
    long long total = 0;
    int rc = SW_OK;
    if (len > 0 && write_all(l->fd, head, len) != 0)
        return SW_ENOTFOUND;
    total += (long long)len;
    for (;;) {
        size_t got = fread(l->win, 1, WIN, in);
        if (got == 0)
            break;
        total += (long long)got;
        if (total > l->o.spool_max) {
            rc = SW_ETOOBIG;
            break;
        }
        if (write_all(l->fd, l->win, got) != 0)
            return SW_ENOTFOUND;
    }
    if (rc == SW_OK && ferror(in))
        return SW_ENOTFOUND;
    l->size = total;
    l->c.spooled = 1;
    return rc;
}

/* l reads the log open as in: a regular file directly, anything else
 * copied first. */
static int attach(sw_lcmlog_t *l, FILE *in, const void *head, size_t len)
{
    struct stat st;
    if (fstat(fileno(in), &st) != 0)
        return SW_ENOTFOUND;
    if (S_ISREG(st.st_mode)) {
        l->fd = fcntl(fileno(in), F_DUPFD_CLOEXEC, 0);
        if (l->fd < 0)
            return SW_ENOTFOUND;
        l->size = (long long)st.st_size;
    } else {
        int rc = spool(l, in, head, len);
        if (rc != SW_OK)
            return rc;
    }
    l->c.size = l->size;
    return SW_OK;
}

sw_lcmlog_t *sw_lcmlog_open_stream(FILE *in, const void *head, size_t len,
                                   const sw_lcmlog_opts_t *o, int *err)
{
    sw_lcmlog_t *l = create(o, err);
    if (!l)
        return NULL;
    *err = attach(l, in, head, len);
    if (*err != SW_OK) {
        int saved = errno;
        sw_lcmlog_close(l);
        errno = saved;
        return NULL;
    }
    return l;
}

sw_lcmlog_t *sw_lcmlog_open(const char *path, const sw_lcmlog_opts_t *o, int *err)
{
    sw_lcmlog_t *l = create(o, err);
    if (!l)
        return NULL;
    FILE *in = fopen(path, "rb");
    *err = in ? attach(l, in, NULL, 0) : SW_ENOTFOUND;
    int saved = errno;
    if (in)
        fclose(in);
    if (*err != SW_OK) {
        sw_lcmlog_close(l);
        errno = saved;
        return NULL;
    }
    return l;
}

void sw_lcmlog_close(sw_lcmlog_t *l)
{
    if (!l)
        return;
    if (l->fd >= 0)
        close(l->fd);
    if (l->has_re)
        regfree(&l->channel);
    free(l->win);
    free(l);
}

void sw_lcmlog_counts(const sw_lcmlog_t *l, sw_lcmlog_counts_t *c)
{
    *c = l->c;
}

/* ---- reading ------------------------------------------------------------------- */

/* Up to len bytes at offset at into buf; the count read (short only at the
 * end of the file, or on an error: l->ioerr). */
static size_t pread_full(sw_lcmlog_t *l, void *buf, size_t len, long long at)
{
    size_t got = 0;
    while (got < len) {
        ssize_t r = pread(l->fd, (char *)buf + got, len - got, (off_t)(at + (long long)got));
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            l->ioerr = errno;
        if (r <= 0)
            break;
        got += (size_t)r;
    }
    l->c.examined += (long long)got;
    return got;
}

/* The bytes from pos on, at least n of them (n <= WIN) unless the file
 * ends first: *avail gets how many there are.  The window keeps what it
 * holds from pos on and reads only what it lacks. */
static const unsigned char *at(sw_lcmlog_t *l, long long pos, size_t n, size_t *avail)
{
    long long wend = l->wbase + (long long)l->wlen;
    if (pos < l->wbase || pos > wend) {
        l->wbase = pos;
        l->wlen = 0;
    } else if (pos + (long long)n > wend && pos > l->wbase) {
        const size_t keep = (size_t)(wend - pos);
        memmove(l->win, l->win + (pos - l->wbase), keep);
        l->wbase = pos;
        l->wlen = keep;
    }
    wend = l->wbase + (long long)l->wlen;
    if (pos + (long long)n > wend && wend < l->size) {
        long long want = WIN - (long long)l->wlen;
        if (want > l->size - wend)
            want = l->size - wend;
        l->wlen += pread_full(l, l->win + l->wlen, (size_t)want, wend);
    }
    *avail = (size_t)(l->wbase + (long long)l->wlen - pos);
    return l->win + (pos - l->wbase);
}

/* Is there a sync word at pos?  From the window if it holds it, else read
 * directly (the window stays where the scan is). */
static int sync_at(sw_lcmlog_t *l, long long pos)
{
    unsigned char b[4];
    if (pos >= l->wbase && pos + 4 <= l->wbase + (long long)l->wlen)
        return get32(l->win + (pos - l->wbase)) == SW_LCMLOG_SYNC;
    return pread_full(l, b, 4, pos) == 4 && get32(b) == SW_LCMLOG_SYNC;
}

/* The first sync word at or after from; the end of the file if none. */
static long long next_sync(sw_lcmlog_t *l, long long from)
{
    static const unsigned char sync[4] = {0xED, 0xA1, 0xDA, 0x01};
    long long pos = from;
    while (pos + 4 <= l->size) {
        size_t avail;
        const unsigned char *p = at(l, pos, WIN, &avail);
        if (avail < 4)
            break; /* a read error */
        const unsigned char *q = p, *end = p + avail - 3;
        while ((q = memchr(q, sync[0], (size_t)(end - q)))) {
            if (!memcmp(q, sync, 4))
                return pos + (q - p);
            q++;
        }
        pos += (long long)avail - 3;
    }
    return l->size;
}

/* Is there a whole event at pos?  1 with e filled, or 0 with why. */
static int check_event(sw_lcmlog_t *l, long long pos, event_t *e, char *why, size_t wlen)
{
    const long long left = l->size - pos;
    size_t avail;
    const unsigned char *p = at(l, pos, SW_LCMLOG_HEADER + SW_LCMLOG_MAX_CHANNEL, &avail);
    if (avail < 4 || get32(p) != SW_LCMLOG_SYNC) {
        snprintf(why, wlen, "%s",
                 avail < 4 ? "stray bytes at the end of the file"
                           : "no sync word (bytes between events)");
        return 0;
    }
    if (avail < SW_LCMLOG_HEADER) {
        snprintf(why, wlen, "the file ends %lld bytes into an event's header", left);
        return 0;
    }
    const int32_t clen = (int32_t)get32(p + 20), dlen = (int32_t)get32(p + 24);
    if (clen < 1 || clen > SW_LCMLOG_MAX_CHANNEL) {
        snprintf(why, wlen, "channel length %ld is not 1 to %d", (long)clen, SW_LCMLOG_MAX_CHANNEL);
        return 0;
    }
    if (dlen < 0) {
        snprintf(why, wlen, "data length %ld is negative", (long)dlen);
        return 0;
    }
    if (dlen > SW_LCMLOG_MAX_DATA) {
        snprintf(why, wlen, "data length %ld is beyond the %ld bytes LCM allows", (long)dlen,
                 SW_LCMLOG_MAX_DATA);
        return 0;
    }
    const long long after = left - SW_LCMLOG_HEADER - clen; /* bytes after the channel */
    if (after < 0) {
        snprintf(why, wlen, "channel length %ld runs past the end of the file", (long)clen);
        return 0;
    }
    if (dlen > after) {
        snprintf(why, wlen,
                 "data length %ld runs past the end of the file (%lld bytes left after the "
                 "channel)",
                 (long)dlen, after);
        return 0;
    }
    memcpy(e->channel, p + SW_LCMLOG_HEADER, (size_t)clen);
    e->channel[clen] = '\0';
    if (memchr(e->channel, '\0', (size_t)clen)) {
        snprintf(why, wlen, "the channel name holds a NUL byte");
        return 0;
    }
    e->start = pos;
    e->data = pos + SW_LCMLOG_HEADER + clen;
    e->end = e->data + dlen;
    e->datalen = dlen;
    e->timestamp = get64(p + 12);
    /* The next event starts right after, or the file ends (within a
     * header's first bytes: those are a region of their own). */
    if (e->end + 4 <= l->size && !sync_at(l, e->end)) {
        snprintf(why, wlen,
                 "no sync word after the event's %ld bytes of data (a length field is wrong)",
                 (long)dlen);
        return 0;
    }
    return 1;
}

/* Event e counted; if it is on the accel channel, *ev is filled with it
 * (returns 1), else 0. */
static int take(sw_lcmlog_t *l, const event_t *e, sw_lcmlog_event_t *ev)
{
    l->c.events++;
    if (regexec(&l->channel, e->channel, 0, NULL, 0) != 0) {
        l->c.other_channels++;
        return 0;
    }
    l->c.on_channel++;
    size_t n = e->datalen < SW_LCMLOG_MAX_FEED ? (size_t)e->datalen : SW_LCMLOG_MAX_FEED;
    size_t avail = 0;
    const unsigned char *data = at(l, e->data, n, &avail);
    if (avail < n)
        n = avail; /* a read error: handed on as it is (truncated) */
    if (!l->have_ts0) {
        l->have_ts0 = 1;
        l->ts0 = e->timestamp;
        l->c.first_utime = e->timestamp;
    }
    l->c.last_utime = e->timestamp; /* what lcm-logger wrote: its clock, not the sensor's */
    int64_t rx_us; /* when lcm-logger received it, relative to the first: exact in double */
    ev->timestamp = e->timestamp;
    ev->rx = __builtin_sub_overflow(e->timestamp, l->ts0, &rx_us) ? NAN : (double)rx_us / 1e6;
    ev->channel = e->channel;
    ev->data = data;
    ev->len = n;
    ev->offset = e->start;
    return 1;
}

/* The region that started at r->offset ends at end. */
static void end_region(sw_lcmlog_t *l, sw_lcmlog_region_t *r, long long end)
{
    r->length = end - r->offset;
    l->c.corrupt_bytes += r->length;
    if (l->o.on_region)
        l->o.on_region(l->o.user, r);
}

int sw_lcmlog_next(sw_lcmlog_t *l, sw_lcmlog_event_t *ev)
{
    while (l->pos < l->size) {
        if (l->o.stop && *l->o.stop) {
            l->c.stopped = 1;
            break;
        }
        event_t *e = &l->cur;
        char why[sizeof l->region.why];
        if (check_event(l, l->pos, e, why, sizeof why)) {
            if (l->in_bad) {
                l->in_bad = 0;
                end_region(l, &l->region, l->pos);
                if (l->o.strict)
                    return SW_EPARSE;
            }
            l->pos = e->end;
            if (take(l, e, ev))
                return 1;
            continue;
        }
        if (l->ioerr) {
            errno = l->ioerr;
            return SW_ENOTFOUND;
        }
        if (!l->in_bad) {
            l->in_bad = 1;
            l->c.corrupt++;
            if (l->c.first_corrupt < 0)
                l->c.first_corrupt = l->pos;
            memset(&l->region, 0, sizeof l->region);
            l->region.offset = l->pos;
            l->region.events = l->c.events;
            memcpy(l->region.why, why, sizeof l->region.why);
        }
        l->pos = next_sync(l, l->pos + 1);
    }
    if (l->ioerr) {
        errno = l->ioerr;
        return SW_ENOTFOUND;
    }
    if (l->in_bad) {
        l->in_bad = 0;
        end_region(l, &l->region, l->pos);
        if (l->o.strict)
            return SW_EPARSE;
    }
    return 0;
}
