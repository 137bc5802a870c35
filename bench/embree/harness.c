/* Native Embree 3 ray-casting harness for the lamplight comparison.
 *
 *   harness V.npy I.npy O.npy D.npy --threads N --runs R --mode MODE [--tile W]
 *           [--t-out T.npy --prim-out P.npy]
 *
 * MODE: 1 (rtcIntersect1), 4 / 8 / 16 (rtcIntersect4/8/16 packets), stream
 * (rtcIntersect1M on 256-ray batches), o1 / o16 / ostream (the same for
 * rtcOccluded, any hit). With --tile W the rays are a row-major W-wide image and
 * packets are 2x2 / 4x2 / 4x4 pixel tiles; otherwise consecutive rays.
 * Rays: tnear 0, tfar inf, one triangle geometry, default build quality.
 * N threads: Embree's build uses its own TBB pool (device config threads=N);
 * tracing runs on N pthreads pulling 4096-ray chunks from an atomic counter.
 * Prints one JSON line: build ms, median wall ms and Mrays/s, CPU seconds
 * (process CPU time, robust when the machine is loaded), BVH bytes (from
 * Embree's memory monitor callback), hits. --t-out/--prim-out write the answers
 * of the first run (float32 t, inf on miss; int32 prim, -1 on miss).
 */
#define _GNU_SOURCE
#include <embree3/rtcore.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>

/* Embree 3's C headers declare plain structs. */
typedef struct RTCIntersectContext RTCIntersectContext;
typedef struct RTCRay RTCRay;
typedef struct RTCRayHit RTCRayHit;
typedef struct RTCRayHit4 RTCRayHit4;
typedef struct RTCRayHit8 RTCRayHit8;
typedef struct RTCRayHit16 RTCRayHit16;
typedef struct RTCRay4 RTCRay4;
typedef struct RTCRay8 RTCRay8;
typedef struct RTCRay16 RTCRay16;

typedef struct { char *data; size_t n; size_t cols; char descr[8]; } Npy;

static void die(const char *m, const char *a) { fprintf(stderr, "harness: %s %s\n", m, a ? a : ""); exit(2); }

static Npy load_npy(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) die("cannot open", path);
  unsigned char pre[12];
  if (fread(pre, 1, 10, f) != 10 || memcmp(pre, "\x93NUMPY", 6)) die("not npy", path);
  size_t hl;
  if (pre[6] == 1) hl = pre[8] | (pre[9] << 8);
  else { if (fread(pre + 10, 1, 2, f) != 2) die("bad", path); hl = pre[8] | (pre[9] << 8) | (pre[10] << 16) | ((size_t)pre[11] << 24); }
  char *h = calloc(hl + 1, 1);
  if (fread(h, 1, hl, f) != hl) die("bad header", path);
  Npy a = {0};
  char *d = strstr(h, "'descr'"); if (!d) die("no descr", path);
  d = strchr(d + 7, '\''); sscanf(d + 1, "%7[^']", a.descr);
  char *s = strstr(h, "'shape'"); if (!s) die("no shape", path);
  s = strchr(s, '(');
  size_t r = 0, c = 1;
  int k = sscanf(s, "(%zu, %zu)", &r, &c);
  if (k < 1) die("bad shape", path);
  if (k == 1) c = 1;
  a.n = r; a.cols = c;
  size_t bytes = r * c * 4;
  a.data = aligned_alloc(64, bytes + 64);
  if (fread(a.data, 1, bytes, f) != bytes) die("short data", path);
  fclose(f); free(h);
  return a;
}

static void save_npy(const char *path, const void *data, size_t n, const char *descr) {
  FILE *f = fopen(path, "wb");
  if (!f) die("cannot write", path);
  char h[128];
  int len = snprintf(h, sizeof h, "{'descr': '%s', 'fortran_order': False, 'shape': (%zu,), }", descr, n);
  while ((10 + len + 1) % 64) h[len++] = ' ';
  h[len++] = '\n';
  unsigned char pre[10] = {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, (unsigned char)(len & 255), (unsigned char)(len >> 8)};
  fwrite(pre, 1, 10, f); fwrite(h, 1, len, f); fwrite(data, 4, n, f); fclose(f);
}

static double now(clockid_t c) { struct timespec t; clock_gettime(c, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }

static atomic_llong bvh_bytes;
static bool monitor(void *ptr, ssize_t bytes, bool post) { (void)ptr; (void)post; atomic_fetch_add(&bvh_bytes, bytes); return true; }

/* Shared state of a tracing run. */
static RTCScene scene;
static const float *O, *D;
static size_t N, W;           /* W = tile image width (0: no tiles) */
static int mode_w, occl, stream_mode;
static float *T; static int32_t *P;
static atomic_size_t next_chunk;
#define CHUNK 4096

/* Ray index of lane l of packet p (packets of w lanes). Tiles: 2x2, 4x2, 4x4. */
static inline size_t ray_index(size_t p, int l, int w) {
  if (!W) return p * w + l;
  int tw = w == 4 ? 2 : 4, th = w / tw;
  size_t tiles_per_row = W / tw;
  size_t ty = p / tiles_per_row, tx = p % tiles_per_row;
  return (ty * th + l / tw) * W + tx * tw + l % tw;
}

static void trace_range(size_t first, size_t last) {  /* in packets of mode_w rays */
  RTCIntersectContext ctx; rtcInitIntersectContext(&ctx);
  if (stream_mode) {
    static _Thread_local RTCRayHit rh[256]; static _Thread_local RTCRay rr[256];
    for (size_t b = first; b < last; b += 256) {
      size_t m = last - b < 256 ? last - b : 256;
      for (size_t j = 0; j < m; j++) {
        size_t i = ray_index(b + j, 0, 1);
        RTCRay *r = occl ? &rr[j] : &rh[j].ray;
        r->org_x = O[3*i]; r->org_y = O[3*i+1]; r->org_z = O[3*i+2]; r->tnear = 0;
        r->dir_x = D[3*i]; r->dir_y = D[3*i+1]; r->dir_z = D[3*i+2]; r->time = 0; r->tfar = INFINITY;
        r->mask = -1; r->id = j; r->flags = 0;
        if (!occl) rh[j].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      }
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      if (occl) rtcOccluded1M(scene, &ctx, rr, m, sizeof(RTCRay));
      else rtcIntersect1M(scene, &ctx, rh, m, sizeof(RTCRayHit));
      for (size_t j = 0; j < m; j++) {
        size_t i = ray_index(b + j, 0, 1);
        if (occl) { T[i] = rr[j].tfar < 0 ? 0.0f : INFINITY; }
        else { int h = rh[j].hit.geomID != RTC_INVALID_GEOMETRY_ID; T[i] = h ? rh[j].ray.tfar : INFINITY; P[i] = h ? (int32_t)rh[j].hit.primID : -1; }
      }
    }
    return;
  }
  if (mode_w == 1) {
    for (size_t i = first; i < last; i++) {
      RTCRayHit rh;
      rh.ray.org_x = O[3*i]; rh.ray.org_y = O[3*i+1]; rh.ray.org_z = O[3*i+2]; rh.ray.tnear = 0;
      rh.ray.dir_x = D[3*i]; rh.ray.dir_y = D[3*i+1]; rh.ray.dir_z = D[3*i+2]; rh.ray.time = 0;
      rh.ray.tfar = INFINITY; rh.ray.mask = -1; rh.ray.id = 0; rh.ray.flags = 0;
      if (occl) { rtcOccluded1(scene, &ctx, &rh.ray); T[i] = rh.ray.tfar < 0 ? 0.0f : INFINITY; continue; }
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &ctx, &rh);
      int h = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      T[i] = h ? rh.ray.tfar : INFINITY; P[i] = h ? (int32_t)rh.hit.primID : -1;
    }
    return;
  }
  /* Packets: RTCRayHit16 is large enough for 4 and 8 too (SoA with stride w). */
  _Alignas(64) RTCRayHit16 rh; _Alignas(64) int valid[16];
  int w = mode_w;
  for (size_t p = first; p < last; p++) {
    float *f = (float *)&rh;
    /* SoA fields in order: org x,y,z, tnear, dir x,y,z, time, tfar, mask, id, flags, then hit */
    for (int l = 0; l < w; l++) {
      size_t i = ray_index(p, l, w);
      valid[l] = -1;
      f[0*w+l] = O[3*i]; f[1*w+l] = O[3*i+1]; f[2*w+l] = O[3*i+2]; f[3*w+l] = 0;
      f[4*w+l] = D[3*i]; f[5*w+l] = D[3*i+1]; f[6*w+l] = D[3*i+2]; f[7*w+l] = 0; f[8*w+l] = INFINITY;
      ((unsigned *)f)[9*w+l] = -1; ((unsigned *)f)[10*w+l] = 0; ((unsigned *)f)[11*w+l] = 0;
      /* hit: Ng x,y,z, u, v, primID, geomID, instID */
      ((unsigned *)f)[18*w+l] = RTC_INVALID_GEOMETRY_ID;
    }
    if (occl) {
      if (w == 4) rtcOccluded4(valid, scene, &ctx, (RTCRay4 *)&rh);
      else if (w == 8) rtcOccluded8(valid, scene, &ctx, (RTCRay8 *)&rh);
      else rtcOccluded16(valid, scene, &ctx, (RTCRay16 *)&rh);
      for (int l = 0; l < w; l++) T[ray_index(p, l, w)] = f[8*w+l] < 0 ? 0.0f : INFINITY;
      continue;
    }
    if (w == 4) rtcIntersect4(valid, scene, &ctx, (RTCRayHit4 *)&rh);
    else if (w == 8) rtcIntersect8(valid, scene, &ctx, (RTCRayHit8 *)&rh);
    else rtcIntersect16(valid, scene, &ctx, &rh);
    for (int l = 0; l < w; l++) {
      size_t i = ray_index(p, l, w);
      int h = ((unsigned *)f)[18*w+l] != RTC_INVALID_GEOMETRY_ID;
      T[i] = h ? f[8*w+l] : INFINITY; P[i] = h ? (int32_t)((unsigned *)f)[17*w+l] : -1;
    }
  }
}

static void *worker(void *arg) {
  (void)arg;
  size_t packets = N / mode_w, per = CHUNK / mode_w;
  for (;;) {
    size_t c = atomic_fetch_add(&next_chunk, 1);
    size_t first = c * per;
    if (first >= packets) break;
    size_t last = first + per < packets ? first + per : packets;
    trace_range(first, last);
  }
  return NULL;
}

static int cmp(const void *a, const void *b) { double x = *(double *)a, y = *(double *)b; return (x > y) - (x < y); }

int main(int argc, char **argv) {
  if (argc < 5) die("usage: harness V.npy I.npy O.npy D.npy [--threads N] [--runs R] [--mode M] [--tile W] [--t-out T] [--prim-out P]", NULL);
  int threads = 1, runs = 5; const char *mode = "1", *tout = NULL, *pout = NULL;
  for (int i = 5; i + 1 < argc; i += 2) {
    if (!strcmp(argv[i], "--threads")) threads = atoi(argv[i+1]);
    else if (!strcmp(argv[i], "--runs")) runs = atoi(argv[i+1]);
    else if (!strcmp(argv[i], "--mode")) mode = argv[i+1];
    else if (!strcmp(argv[i], "--tile")) W = strtoul(argv[i+1], NULL, 10);
    else if (!strcmp(argv[i], "--t-out")) tout = argv[i+1];
    else if (!strcmp(argv[i], "--prim-out")) pout = argv[i+1];
    else die("unknown flag", argv[i]);
  }
  Npy v = load_npy(argv[1]), f = load_npy(argv[2]), o = load_npy(argv[3]), d = load_npy(argv[4]);
  if (strcmp(v.descr, "<f4") || strcmp(o.descr, "<f4") || strcmp(d.descr, "<f4") || o.n != d.n) die("need float32 V/O/D of equal length", NULL);
  O = (float *)o.data; D = (float *)d.data; N = o.n;
  occl = mode[0] == 'o';
  const char *m = occl ? mode + 1 : mode;
  stream_mode = !strcmp(m, "stream");
  mode_w = stream_mode ? 1 : atoi(m);
  if (!(mode_w == 1 || mode_w == 4 || mode_w == 8 || mode_w == 16)) die("bad mode", mode);
  if (W && (W % 4 || (N / W) % 4)) die("tile width must divide into 4x4 tiles", NULL);
  if (N % mode_w) die("ray count must be a multiple of the packet width", NULL);

  char cfg[64]; snprintf(cfg, sizeof cfg, "threads=%d", threads);
  RTCDevice dev = rtcNewDevice(cfg);
  rtcSetDeviceMemoryMonitorFunction(dev, monitor, NULL);
  double best_build = 1e30, builds[5];
  for (int b = 0; b < 3; b++) {
    scene = rtcNewScene(dev);
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, v.n);
    memcpy(vb, v.data, v.n * 12);
    unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, f.n);
    memcpy(ib, f.data, f.n * 12);
    rtcCommitGeometry(g); rtcAttachGeometry(scene, g); rtcReleaseGeometry(g);
    long long before = atomic_load(&bvh_bytes);
    double t0 = now(CLOCK_MONOTONIC);
    rtcCommitScene(scene);
    builds[b] = now(CLOCK_MONOTONIC) - t0;
    if (builds[b] < best_build) best_build = builds[b];
    if (b < 2) rtcReleaseScene(scene);
    else bvh_bytes = atomic_load(&bvh_bytes) - before;
  }
  qsort(builds, 3, sizeof(double), cmp);
  long long bytes = atomic_load(&bvh_bytes);

  T = aligned_alloc(64, N * 4 + 64); P = aligned_alloc(64, N * 4 + 64);
  double walls[64], cpus[64];
  if (runs > 64) runs = 64;
  for (int r = -1; r < runs; r++) {  /* r = -1: warm-up, its answers are saved */
    atomic_store(&next_chunk, 0);
    pthread_t th[64];
    double w0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    for (int t = 0; t < threads; t++) pthread_create(&th[t], NULL, worker, NULL);
    for (int t = 0; t < threads; t++) pthread_join(th[t], NULL);
    double w = now(CLOCK_MONOTONIC) - w0, c = now(CLOCK_PROCESS_CPUTIME_ID) - c0;
    if (r < 0) {
      if (tout) save_npy(tout, T, N, "<f4");
      if (pout && !occl) save_npy(pout, P, N, "<i4");
      continue;
    }
    walls[r] = w; cpus[r] = c;
  }
  qsort(walls, runs, sizeof(double), cmp); qsort(cpus, runs, sizeof(double), cmp);
  size_t hits = 0;
  for (size_t i = 0; i < N; i++) hits += isfinite(T[i]);
  double wm = walls[runs / 2], cm = cpus[runs / 2];
  printf("{\"mode\": \"%s\", \"threads\": %d, \"tile\": %zu, \"rays\": %zu, \"build_ms\": %.2f, \"wall_ms\": %.2f, \"mrays_wall\": %.3f, "
         "\"cpu_s\": %.4f, \"mrays_per_cpu_s\": %.3f, \"bvh_bytes\": %lld, \"triangles\": %zu, \"hits\": %zu}\n",
         mode, threads, W, N, builds[1] * 1e3, wm * 1e3, N / wm / 1e6, cm, N / cm / 1e6, bytes, f.n, hits);
  rtcReleaseScene(scene); rtcReleaseDevice(dev);
  return 0;
}
