/* A minimal FMI 2.0 co-simulation host in C: loads an FMU's shared library
 * directly (dlopen), runs the built-in move with one communication step per
 * internal step, prints the requested Real variables as CSV on stdout and
 * the median time per fmi2DoStep on stderr. The resource location it passes
 * is the `resources` folder of the extracted FMU the library lies in
 * (LIBRARY.so is `<FMU>/binaries/linux64/<id>.so`), as a file: URI.
 *
 *   host LIBRARY.so GUID START STOP STEP VR...       run from START, print t,VR...
 *   host LIBRARY.so GUID START --bad VR VALUE        expect fmi2Error from
 *                                                     fmi2ExitInitializationMode,
 *                                                     fmi2DoStep after it, and
 *                                                     fmi2DoStep after
 *                                                     fmi2FreeInstance (and no
 *                                                     crash on a second free)
 *
 * Build: cc -O2 -o host host.c -ldl -lm
 */
#include <dlfcn.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef void *fmi2Component;
typedef unsigned int fmi2ValueReference;
typedef int fmi2Status; /* 0 OK, 1 Warning, 2 Discard, 3 Error, 4 Fatal */

typedef struct {
    void (*logger)(void *, const char *, fmi2Status, const char *, const char *, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;

static void logger(void *env, const char *name, fmi2Status status, const char *category, const char *message, ...) {
    va_list args;
    (void)env;
    fprintf(stderr, "[%s %s %d] ", name, category, status);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void *symbol(void *library, const char *name) {
    void *f = dlsym(library, name);
    if (!f) {
        fprintf(stderr, "host: %s missing\n", name);
        exit(2);
    }
    return f;
}

/* The file: URI of the `resources` folder three levels above `library`
 * (percent-escaping every byte but unreserved characters and '/'), or "" if
 * the library's path cannot be resolved. */
static char *resource_location(const char *library) {
    static char uri[3 * 4096 + 32];
    char *path = realpath(library, NULL);
    if (!path) {
        uri[0] = '\0';
        return uri;
    }
    for (int level = 0; level < 3; level++) {
        char *slash = strrchr(path, '/');
        if (slash) {
            *slash = '\0';
        }
    }
    char *end = uri + sprintf(uri, "file://");
    for (const unsigned char *c = (const unsigned char *)path; *c && end < uri + sizeof uri - 16; c++) {
        if ((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') || strchr("-._~/", *c)) {
            *end++ = (char)*c;
        } else {
            end += sprintf(end, "%%%02X", *c);
        }
    }
    strcpy(end, "/resources/");
    free(path);
    return uri;
}

static int compare(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv) {
    if (argc < 6) {
        fprintf(stderr, "usage: host LIBRARY.so GUID START STOP STEP VR... | host LIBRARY.so GUID START --bad VR VALUE\n");
        return 2;
    }
    void *library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!library) {
        fprintf(stderr, "host: %s\n", dlerror());
        return 2;
    }
    fmi2Component (*instantiate)(const char *, int, const char *, const char *, const fmi2CallbackFunctions *, int, int) =
        symbol(library, "fmi2Instantiate");
    fmi2Status (*setup)(fmi2Component, int, double, double, int, double) = symbol(library, "fmi2SetupExperiment");
    fmi2Status (*enter)(fmi2Component) = symbol(library, "fmi2EnterInitializationMode");
    fmi2Status (*exit_init)(fmi2Component) = symbol(library, "fmi2ExitInitializationMode");
    fmi2Status (*set_real)(fmi2Component, const fmi2ValueReference *, size_t, const double *) = symbol(library, "fmi2SetReal");
    fmi2Status (*get_real)(fmi2Component, const fmi2ValueReference *, size_t, double *) = symbol(library, "fmi2GetReal");
    fmi2Status (*do_step)(fmi2Component, double, double, int) = symbol(library, "fmi2DoStep");
    fmi2Status (*terminate)(fmi2Component) = symbol(library, "fmi2Terminate");
    void (*free_instance)(fmi2Component) = symbol(library, "fmi2FreeInstance");

    fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
    fmi2Component c = instantiate("host", 1, argv[2], resource_location(argv[1]), &callbacks, 0, 0);
    if (!c) {
        fprintf(stderr, "host: fmi2Instantiate failed\n");
        return 1;
    }
    double start = strtod(argv[3], NULL);
    if (setup(c, 0, 0.0, start, 0, 0.0) != 0 || enter(c) != 0) {
        fprintf(stderr, "host: initialisation failed\n");
        return 1;
    }
    if (strcmp(argv[4], "--bad") == 0) {
        fmi2ValueReference vr = (fmi2ValueReference)strtoul(argv[5], NULL, 10);
        double value = argc > 6 ? strtod(argv[6], NULL) : -1.0;
        set_real(c, &vr, 1, &value);
        fmi2Status status = exit_init(c);
        /* the instance must still answer after the error */
        fmi2Status again = do_step(c, start, 0.01, 1);
        free_instance(c);
        /* a host's misuse after the free: an error status, not a crash */
        fmi2Status freed = do_step(c, start, 0.01, 1);
        free_instance(c);
        printf("fmi2ExitInitializationMode: %d, fmi2DoStep after it: %d, fmi2DoStep and fmi2FreeInstance after "
               "fmi2FreeInstance: %d\n", status, again, freed);
        return (status == 3 && again == 3 && freed == 3) ? 0 : 1;
    }
    /* fmi2Warning (1): the audit found something, the run goes on */
    long warnings = 0;
    fmi2Status started = exit_init(c);
    if (started > 1) {
        fprintf(stderr, "host: fmi2ExitInitializationMode failed\n");
        return 1;
    }
    warnings += started == 1;
    double stop = strtod(argv[4], NULL), h = strtod(argv[5], NULL);
    size_t n = (size_t)(argc - 6);
    fmi2ValueReference *vr = malloc(n * sizeof *vr);
    double *values = malloc(n * sizeof *values);
    for (size_t i = 0; i < n; i++) vr[i] = (fmi2ValueReference)strtoul(argv[6 + i], NULL, 10);
    long steps = lround((stop - start) / h);
    double *times = malloc((size_t)steps * sizeof *times);
    for (long k = 0; k <= steps; k++) {
        double t = start + k * h;
        if (k > 0) {
            struct timespec a, b;
            clock_gettime(CLOCK_MONOTONIC, &a);
            fmi2Status status = do_step(c, start + (k - 1) * h, h, 1);
            clock_gettime(CLOCK_MONOTONIC, &b);
            times[k - 1] = (b.tv_sec - a.tv_sec) * 1e6 + (b.tv_nsec - a.tv_nsec) * 1e-3;
            if (status > 1) {
                fprintf(stderr, "host: fmi2DoStep failed at t = %g\n", t);
                return 1;
            }
            warnings += status == 1;
        }
        get_real(c, vr, n, values);
        printf("%.17g", t);
        for (size_t i = 0; i < n; i++) printf(",%.17g", values[i]);
        printf("\n");
    }
    qsort(times, (size_t)steps, sizeof *times, compare);
    fprintf(stderr, "host: %ld steps, median fmi2DoStep %.2f us, %ld warnings\n", steps, times[steps / 2], warnings);
    terminate(c);
    free_instance(c);
    free(vr);
    free(values);
    free(times);
    dlclose(library);
    return 0;
}
