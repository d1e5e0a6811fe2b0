/* png_read_test.c: text chunks written by cv_png_write read back by key
 * (what --resume relies on); missing keys and non-PNG files fail cleanly. */
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "output/metadata.h"
#include "output/png_read.h"
#include "output/png_write.h"
#include "tests/tap.h"

int main(void)
{
    char dir[] = "/tmp/cv-png-read-XXXXXX";
    if (!mkdtemp(dir))
        return tap_skip_all("no temp dir");
    char *path = cv_xasprintf("%s/a.png", dir);
    float px[2 * 2 * 3] = {0, 0.5f, 1, 1, 0, 0.25f, 0.1f, 0.2f, 0.3f, 1, 1, 1};
    struct cv_metadata *m = cv_metadata_new();
    cv_metadata_set_string(m, "cavalry.settingsHash", "0123456789abcdef");
    cv_metadata_set_string(m, "cavalry.status", "complete");
    struct cv_error err = {{0}};
    bool ok = cv_png_write(path, &(struct cv_png_params){.pixels = px, .width = 2, .height = 2,
                                                          .channels = 3, .meta = m},
                           &err);
    tap_ok(ok, "write: %s", ok ? "" : err.msg);
    char *v = NULL;
    tap_ok(cv_png_read_text(path, "cavalry.settingsHash", &v, &err) && strcmp(v, "0123456789abcdef") == 0,
           "hash reads back");
    free(v);
    v = NULL;
    tap_ok(cv_png_read_text(path, "cavalry.status", &v, &err) && strcmp(v, "complete") == 0,
           "status reads back");
    free(v);
    tap_ok(!cv_png_read_text(path, "nope", &v, &err) && strstr(err.msg, "nope"),
           "missing key: %s", err.msg);
    char *bad = cv_xasprintf("%s/b.png", dir);
    FILE *f = fopen(bad, "wb");
    fputs("not a png at all", f);
    fclose(f);
    tap_ok(!cv_png_read_text(bad, "x", &v, &err) && strstr(err.msg, "not a PNG"), "not a PNG: %s",
           err.msg);
    tap_ok(!cv_png_read_text("/nonexistent/c.png", "x", &v, &err), "missing file fails");
    remove(path);
    remove(bad);
    rmdir(dir);
    free(path);
    free(bad);
    cv_metadata_destroy(&m);
    return tap_done();
}
