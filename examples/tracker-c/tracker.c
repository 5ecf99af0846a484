/* Reference tracker stub, in C99 with LCM's C library (docs/hardware.md, "A tracking system"):
 * feeds ahhs-fitness with the organism's body poses instead of the sim. On every SIM/CLOCK of a
 * running or finished episode it publishes SIM/STATE with one body per module (episode, tick and
 * sim_time copied from the clock), from hw_read_pose, the only tracker access: on a real system
 * it asks the motion capture for the module's marker. Here it emulates an organism whose modules
 * all move 1 cm per tick along x.
 *
 *   ahhs-example-tracker --arena NAME --modules N [--lcm-url URL] [--seconds S] */
#define _POSIX_C_SOURCE 200809L
#include <lcm/lcm.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ahhs_sim_clock_t.h"
#include "ahhs_sim_state_t.h"

#define MAX_MODULES 64

static volatile sig_atomic_t stop_requested = 0;
static void on_signal(int sig) {
  (void)sig;
  stop_requested = 1;
}

static double now_s(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int64_t now_utime(void) {
  struct timespec t;
  clock_gettime(CLOCK_REALTIME, &t);
  return (int64_t)t.tv_sec * 1000000 + t.tv_nsec / 1000;
}

/* ---- The tracker (emulated): replace on a real system. Metres, world frame. ---- */
static void hw_read_pose(int module, int64_t tick, double position[3]) {
  position[0] = 0.01 * (double)tick - 0.1 * module;
  position[1] = 0;
  position[2] = 0.05;
}

struct tracker {
  lcm_t* lcm;
  int modules;
  char state_channel[256];
  long states;
};

static void on_clock(const lcm_recv_buf_t* rbuf, const char* channel, const ahhs_sim_clock_t* c,
                     void* user) {
  (void)rbuf;
  (void)channel;
  struct tracker* t = user;
  if (c->run_state != AHHS_SIM_CLOCK_T_RUNNING && c->run_state != AHHS_SIM_CLOCK_T_FINISHED) return;
  int32_t module[MAX_MODULES];
  int8_t shape[MAX_MODULES];
  double px[MAX_MODULES], py[MAX_MODULES], pz[MAX_MODULES], qw[MAX_MODULES], qx[MAX_MODULES],
      qy[MAX_MODULES], qz[MAX_MODULES], sx[MAX_MODULES], sy[MAX_MODULES], sz[MAX_MODULES],
      mass[MAX_MODULES];
  for (int k = 0; k < t->modules; ++k) {
    double p[3];
    hw_read_pose(k, c->tick, p);
    module[k] = k;
    shape[k] = AHHS_SIM_STATE_T_SHAPE_BOX;
    px[k] = p[0];
    py[k] = p[1];
    pz[k] = p[2];
    qw[k] = 1;
    qx[k] = qy[k] = qz[k] = 0;
    sx[k] = sy[k] = sz[k] = 0.1;
    mass[k] = 0.2; /* moving bodies: mass > 0 */
  }
  ahhs_sim_state_t m;
  memset(&m, 0, sizeof m);
  m.utime = now_utime();
  m.episode = c->episode; /* copied from the clock: the monitor drops other episodes */
  m.tick = c->tick;
  m.sim_time = c->sim_time;
  m.num_bodies = (int16_t)t->modules;
  m.module = module;
  m.shape = shape;
  m.px = px;
  m.py = py;
  m.pz = pz;
  m.qw = qw;
  m.qx = qx;
  m.qy = qy;
  m.qz = qz;
  m.sx = sx;
  m.sy = sy;
  m.sz = sz;
  m.mass = mass;
  if (ahhs_sim_state_t_publish(t->lcm, t->state_channel, &m) == 0) ++t->states;
}

static int usage(const char* why) {
  fprintf(stderr, "ahhs-example-tracker: %s\n", why);
  fprintf(stderr,
          "usage: ahhs-example-tracker --arena NAME --modules N [--lcm-url URL] [--seconds S]\n");
  return 2;
}

int main(int argc, char** argv) {
  const char* url = "udpm://239.255.76.67:7667?ttl=0";
  const char* arena = NULL;
  int modules = 0;
  double seconds = 0;
  for (int k = 1; k < argc; ++k) {
    if (k + 1 >= argc) return usage("every option takes a value");
    if (strcmp(argv[k], "--lcm-url") == 0)
      url = argv[++k];
    else if (strcmp(argv[k], "--arena") == 0)
      arena = argv[++k];
    else if (strcmp(argv[k], "--modules") == 0)
      modules = atoi(argv[++k]);
    else if (strcmp(argv[k], "--seconds") == 0)
      seconds = atof(argv[++k]);
    else
      return usage("unknown option");
  }
  if (arena == NULL || modules < 1 || modules > MAX_MODULES || seconds < 0)
    return usage("--arena and --modules (1 to 64) are required");
  struct tracker t;
  memset(&t, 0, sizeof t);
  t.modules = modules;
  t.lcm = lcm_create(url);
  if (t.lcm == NULL) {
    fprintf(stderr, "ahhs-example-tracker: cannot open the bus %s\n", url);
    return 1;
  }
  char channel[256];
  snprintf(channel, sizeof channel, "%s/SIM/CLOCK", arena);
  ahhs_sim_clock_t_subscription_t* clock_sub =
      ahhs_sim_clock_t_subscribe(t.lcm, channel, on_clock, &t);
  snprintf(t.state_channel, sizeof t.state_channel, "%s/SIM/STATE", arena);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  const double end = now_s() + seconds;
  while (!stop_requested && (seconds == 0 || now_s() < end)) lcm_handle_timeout(t.lcm, 100);
  printf("tracker of %d modules: %ld states sent on %s\n", modules, t.states, t.state_channel);
  ahhs_sim_clock_t_unsubscribe(t.lcm, clock_sub);
  lcm_destroy(t.lcm);
  return 0;
}
