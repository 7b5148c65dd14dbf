/* STREAM-triad bandwidth, single thread: a[i] = b[i] + s * c[i].
 * Usage: stream [log2_n [repetitions]]   (defaults: 2^25 doubles per array, best of 10)
 * Prints one line: "triad_GBps <best> n <n> reps <r> best_s <t>", counting 3 * 8 * n bytes per
 * repetition (STREAM convention: no write-allocate traffic).
 * Build: gcc -O3 -o stream stream.c   (bench/run.py does this) */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv) {
  const int lg = argc > 1 ? atoi(argv[1]) : 25;
  const int reps = argc > 2 ? atoi(argv[2]) : 10;
  const size_t n = (size_t)1 << lg;
  double *a = aligned_alloc(64, n * sizeof(double));
  double *b = aligned_alloc(64, n * sizeof(double));
  double *c = aligned_alloc(64, n * sizeof(double));
  if (!a || !b || !c) {
    fprintf(stderr, "stream: out of memory\n");
    return 1;
  }
  for (size_t i = 0; i < n; ++i) { /* first touch, and values that stay finite */
    a[i] = 0.0;
    b[i] = 1.0;
    c[i] = 2.0;
  }
  const double s = 3.0;
  double best = 1e30;
  for (int r = 0; r < reps; ++r) {
    const double t0 = now();
    for (size_t i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    const double t = now() - t0;
    if (t < best) best = t;
    b[r % n] = a[(r * 7919) % n]; /* keep every repetition live */
  }
  double check = 0.0;
  for (size_t i = 0; i < n; i += 4096) check += a[i];
  printf("triad_GBps %.3f n %zu reps %d best_s %.6f check %.1f\n", 3.0 * 8.0 * (double)n / best / 1e9,
         n, reps, best, check);
  free(a);
  free(b);
  free(c);
  return 0;
}
