/* SPDX-License-Identifier: GPL-3.0-or-later */
/* test_record.c - the record writer (src/cli/output/record.c) alone: JSON
 * numbers with the 9 digits %.9g printed and null where a value is not
 * finite, members in the order they were set, strings made valid UTF-8
 * (one U+FFFD per maximal subpart, Unicode 3.9, as Python's
 * errors="replace" reads the bytes), and CSV rows read off a record:
 * members of members, absent members, true and false, lists, and text
 * cells quoted as RFC 4180 says and kept from formulas as OWASP says.
 * The expected texts are written out by hand from those rules. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "record.h"

/* What f received, as a string (free it). */
static char *taken(FILE *f, char **buf)
{
    assert_int_equal(fclose(f), 0);
    return *buf;
}

static void test_json(void **state)
{
    (void)state;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    json_t *o = sw_cli_rec_new();
    sw_cli_rec_num(o, "pi", M_PI);
    sw_cli_rec_num(o, "none", NAN);
    sw_cli_rec_num(o, "inf", INFINITY);
    sw_cli_rec_int(o, "n", 42);
    sw_cli_rec_bool(o, "b", 7);
    sw_cli_rec_text(o, "null", NULL);
    /* "a", an overlong NUL (2 subparts: C0 can never begin a character,
     * 80 alone), a cut 3-byte sequence (1 subpart), a surrogate (3), "z" */
    sw_cli_rec_text(o, "s", "a\xc0\x80\xe2\x82z\xed\xa0\x80\n\"");
    json_t *a = sw_cli_rec_arr(o, "list");
    sw_cli_rec_num(a, NULL, 0.1);
    sw_cli_rec_text(a, NULL, "x");
    assert_int_equal(sw_cli_rec_write(f, o, SW_CLI_REC_LINE), 0);
    char *s = taken(f, &buf);
    assert_string_equal(
        s,
        "{\"pi\": 3.14159265, \"none\": null, \"inf\": null, \"n\": 42, \"b\": true, "
        "\"null\": null, \"s\": \"a\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbdz"
        "\xef\xbf\xbd\xef\xbf\xbd\xef\xbf\xbd\\n\\\"\", \"list\": [0.1, \"x\"]}\n");
    free(s);
}

/* A record whose member could not be made is refused, not written short. */
static void test_failed(void **state)
{
    (void)state;
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    json_t *o = sw_cli_rec_new();
    sw_cli_rec_int(o, "a", 1);
    sw_cli_rec_put(o, "b", NULL); /* as when memory runs out */
    assert_int_equal(sw_cli_rec_write(f, o, SW_CLI_REC_LINE), -1);
    char *s = taken(f, &buf);
    assert_string_equal(s, "");
    free(s);
    o = sw_cli_rec_new(); /* the next record starts afresh */
    sw_cli_rec_int(o, "a", 1);
    assert_non_null(s = sw_cli_rec_line(o));
    assert_string_equal(s, "{\"a\": 1}");
    free(s);
}

static void test_csv(void **state)
{
    (void)state;
    json_t *o = sw_cli_rec_new();
    sw_cli_rec_text(o, "name", "=SUM(A1),x");
    sw_cli_rec_bool(o, "over", 1);
    sw_cli_rec_bool(o, "under", 0);
    json_t *in = sw_cli_rec_obj(o, "input");
    sw_cli_rec_num(in, "rate", 1000.0);
    sw_cli_rec_num(in, "gap", NAN);
    sw_cli_rec_text(in, "why", "say \"hi\"");
    json_t *a = sw_cli_rec_arr(o, "saved");
    sw_cli_rec_text(a, NULL, "frame, soft");
    sw_cli_rec_text(a, NULL, "cushion");
    sw_cli_rec_int(o, "n", -3);
    sw_cli_rec_text(o, "minus", "-1");
    const sw_cli_column_t c[] = {
        {.name = "package", .path = "name"},
        {.name = "over"},
        {.name = "under"},
        {.name = "rate", .path = "input.rate"},
        {.name = "gap", .path = "input.gap"},
        {.name = "why", .path = "input.why"},
        {.name = "saved"},
        {.name = "n"},
        {.name = "minus"},
        {.name = "absent"},
        {.name = "trials", .path = "sf.trials", .missing = "0"},
    };
    const size_t n = sizeof c / sizeof c[0];
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    fputs("index", f);
    sw_cli_csv_header(f, c, n);
    fputs("\n1", f);
    sw_cli_csv_row(f, o, c, n);
    char *s = taken(f, &buf);
    assert_string_equal(s,
                        "index,package,over,under,rate,gap,why,saved,n,minus,absent,trials\n"
                        "1,\"'=SUM(A1),x\",1,0,1000,,\"say \"\"hi\"\"\",\"frame, soft; cushion\","
                        "-3,'-1,,0");
    free(s);
    json_decref(o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_json),
        cmocka_unit_test(test_failed),
        cmocka_unit_test(test_csv),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
