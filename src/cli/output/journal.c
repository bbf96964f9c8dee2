/* SPDX-License-Identifier: GPL-3.0-or-later */
/* journal.c - alarm lines and priority prefixes for the journal (journal.h). */
#include "journal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "text.h"

int sw_cli_stderr_is_journal(void)
{
    static int known, journal;
    if (known)
        return journal;
    known = 1;
    const char *e = getenv("JOURNAL_STREAM");
    unsigned long long dev, ino;
    char end;
    struct stat st;
    if (!e || sscanf(e, "%llu:%llu%c", &dev, &ino, &end) != 2 || fstat(STDERR_FILENO, &st) != 0)
        return journal = 0;
    return journal = (unsigned long long)st.st_dev == dev && (unsigned long long)st.st_ino == ino;
}

const char *sw_cli_journal_prefix(int prio)
{
    static const char *const p[8] = {"<0>", "<1>", "<2>", "<3>", "<4>", "<5>", "<6>", "<7>"};
    return sw_cli_stderr_is_journal() && prio >= 0 && prio < 8 ? p[prio] : "";
}

int sw_cli_alarm_priority(sw_alarm_level level)
{
    switch (level) {
        case SW_ALARM_LEVEL_CRITICAL: return SW_PRIO_CRIT;
        case SW_ALARM_LEVEL_WARN: return SW_PRIO_WARNING;
        case SW_ALARM_LEVEL_INFO: break;
    }
    return SW_PRIO_INFO;
}

void sw_cli_iso_time(char *buf, size_t len, int64_t us)
{
    /* floor division: times before 1970 keep their ms in [0, 999] */
    int64_t s = us / 1000000, rem = us % 1000000;
    if (rem < 0) {
        s--;
        rem += 1000000;
    }
    time_t t = (time_t)s;
    struct tm tm;
    if (!gmtime_r(&t, &tm)) {
        snprintf(buf, len, "(time %lld us)", (long long)us);
        return;
    }
    char date[24];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", &tm);
    snprintf(buf, len, "%s.%03dZ", date, (int)(rem / 1000));
}

/* s into dst (cap bytes, NUL-terminated) for a line on a terminal or in
 * the journal: control characters and bytes that are not UTF-8 as '?'
 * (text.h), '"' replaced by '\''. */
static void clean(char *dst, size_t cap, const char *s)
{
    sw_cli_term_text(dst, cap, s ? s : "", s ? strlen(s) : 0);
    for (char *p = dst; *p; p++)
        if (*p == '"')
            *p = '\'';
}

size_t sw_cli_alarm_format(char *buf, size_t len, const sw_cli_alarm_line_t *a)
{
    char when[40], name[SW_NAME_MAX], text[SW_ALARM_TEXT_MAX], nums[96];
    sw_cli_iso_time(when, sizeof when, a->wall_us);
    clean(name, sizeof name, a->package);
    clean(text, sizeof text, a->text);
    const int quote = strpbrk(name, " \t'") != NULL || (a->package && !name[0]);
    if (!a->package)
        snprintf(nums, sizeof nums, "theta=- margin=-");
    else
        snprintf(nums, sizeof nums, "theta=%.4f margin=%.4f", a->theta, a->margin);
    /* The reserve goes after the margin when there is one (alarm_t's -1:
     * none yet, or off) */
    if (isfinite(a->reserve_g) && a->reserve_g >= 0.0) {
        size_t used = strlen(nums);
        snprintf(nums + used, sizeof nums - used, " reserve_g=%.3f", a->reserve_g);
    }
    int n =
        snprintf(buf, len, "swaywatch: alarm %s level=%s package=%s%s%s kind=%s %s text=\"%s\"",
                 when, sw_alarm_level_name(a->level), quote ? "\"" : "", a->package ? name : "-",
                 quote ? "\"" : "", sw_alarm_kind_name(a->kind), nums, text);
    return n < 0 ? 0 : (size_t)n;
}

void sw_cli_alarm_print(const sw_cli_alarm_line_t *a)
{
    char line[512];
    const char *prefix = sw_cli_journal_prefix(sw_cli_alarm_priority(a->level));
    size_t p = strlen(prefix);
    memcpy(line, prefix, p);
    sw_cli_alarm_format(line + p, sizeof line - p - 1, a);
    size_t n = strlen(line);
    line[n++] = '\n';
    /* One write: the line is not split among other writers of the stream. */
    fwrite(line, 1, n, stderr);
}
