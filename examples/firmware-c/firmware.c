/* Reference firmware of one gait module, in C99 with LCM's C library and the C types that
 * `lcm-gen -c` makes from lcmtypes/ (docs/hardware.md). The shape a microcontroller-class Linux
 * board runs: one process, one LCM handle, no threads.
 *
 * On every SIM/CLOCK tick of a running episode it publishes the module's SENSORS (episode and
 * tick copied from the clock), and it servos the hinge to the target of every valid HINGE
 * command of the current episode. The three hw_* functions are the only hardware access: on a
 * real board they read the proximity sensors and the hinge encoder and drive the servo. Here
 * they emulate a module with nothing in sight and a servo that turns at 3 rad/s.
 *
 *   ahhs-example-firmware --arena NAME --id N [--lcm-url URL] [--seconds S]
 *
 * It also watches its own SENSORS channel: readings it did not send mean that someone else (a
 * sim without --hardware-modules N) speaks for this module; they are counted and reported.
 * Exit status: 0, or 2 for bad options. */
#define _POSIX_C_SOURCE 200809L
#include <lcm/lcm.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ahhs_hinge_command_t.h"
#include "ahhs_module_sensors_t.h"
#include "ahhs_sim_clock_t.h"

#define NUM_SENSORS 4 /* gait: 0 up, 1 forward, 2 down, 3 backward */
#define HINGE_LIMIT 1.5707963267948966
#define SERVO_SPEED 3.0 /* rad/s of the emulated servo */

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

/* ---- The hardware (emulated): replace these three on a real board. ---- */
static double servo_angle = 0, servo_target = 0, servo_time = -1;

static double hw_read_proximity(int slot) {
  (void)slot;
  return 0.0; /* nothing within 0.2 m */
}

static double hw_read_hinge_angle(void) {
  const double t = now_s();
  if (servo_time >= 0) {
    const double step = SERVO_SPEED * (t - servo_time);
    const double error = servo_target - servo_angle;
    servo_angle += fabs(error) <= step ? error : (error > 0 ? step : -step);
  }
  servo_time = t;
  return servo_angle;
}

static void hw_set_hinge_target(double radians) {
  hw_read_hinge_angle(); /* bring the emulated servo up to now first */
  servo_target = radians < -HINGE_LIMIT  ? -HINGE_LIMIT
                 : radians > HINGE_LIMIT ? HINGE_LIMIT
                                         : radians;
}

/* ---- The protocol. ---- */
struct firmware {
  lcm_t* lcm;
  int id;
  char sensors_channel[256];
  int64_t episode; /* of the latest running clock */
  int64_t sent_utime[8];
  long readings, commands, dropped_commands, foreign_readings;
};

static void on_clock(const lcm_recv_buf_t* rbuf, const char* channel, const ahhs_sim_clock_t* c,
                     void* user) {
  (void)rbuf;
  (void)channel;
  struct firmware* f = user;
  if (c->run_state != AHHS_SIM_CLOCK_T_RUNNING) return; /* readings only while running */
  f->episode = c->episode;
  double values[NUM_SENSORS];
  int8_t present[NUM_SENSORS];
  for (int k = 0; k < NUM_SENSORS; ++k) {
    values[k] = hw_read_proximity(k);
    present[k] = 1;
  }
  int8_t actuator_present[1] = {1};
  ahhs_module_sensors_t m;
  memset(&m, 0, sizeof m);
  m.utime = now_utime();
  m.episode = c->episode; /* copied from the clock */
  m.tick = c->tick;
  m.module = f->id;
  m.sim_time = c->sim_time;
  m.num_sensors = NUM_SENSORS;
  m.values = values;
  m.present = present;
  m.hinge_angle = hw_read_hinge_angle();
  m.num_actuators = 1;
  m.actuator_present = actuator_present;
  f->sent_utime[f->readings % 8] = m.utime;
  if (ahhs_module_sensors_t_publish(f->lcm, f->sensors_channel, &m) == 0) ++f->readings;
}

static void on_sensors(const lcm_recv_buf_t* rbuf, const char* channel,
                       const ahhs_module_sensors_t* m, void* user) {
  (void)rbuf;
  (void)channel;
  struct firmware* f = user;
  for (int k = 0; k < 8; ++k)
    if (f->sent_utime[k] == m->utime) return; /* our own, looped back */
  ++f->foreign_readings;
}

static void on_hinge(const lcm_recv_buf_t* rbuf, const char* channel, const ahhs_hinge_command_t* h,
                     void* user) {
  (void)rbuf;
  (void)channel;
  struct firmware* f = user;
  if (h->episode != f->episode || h->module != f->id || !isfinite(h->target_angle)) {
    ++f->dropped_commands; /* another episode, another module, or no target */
    return;
  }
  hw_set_hinge_target(h->target_angle);
  ++f->commands;
}

static int usage(const char* why) {
  fprintf(stderr, "ahhs-example-firmware: %s\n", why);
  fprintf(stderr,
          "usage: ahhs-example-firmware --arena NAME --id N [--lcm-url URL] [--seconds S]\n");
  return 2;
}

int main(int argc, char** argv) {
  const char* url = "udpm://239.255.76.67:7667?ttl=0";
  const char* arena = NULL;
  int id = -1;
  double seconds = 0; /* 0: until SIGINT or SIGTERM */
  for (int k = 1; k < argc; ++k) {
    if (k + 1 >= argc) return usage("every option takes a value");
    if (strcmp(argv[k], "--lcm-url") == 0)
      url = argv[++k];
    else if (strcmp(argv[k], "--arena") == 0)
      arena = argv[++k];
    else if (strcmp(argv[k], "--id") == 0)
      id = atoi(argv[++k]);
    else if (strcmp(argv[k], "--seconds") == 0)
      seconds = atof(argv[++k]);
    else
      return usage("unknown option");
  }
  if (arena == NULL || id < 0 || seconds < 0) return usage("--arena and --id are required");

  struct firmware f;
  memset(&f, 0, sizeof f);
  f.id = id;
  f.episode = -1;
  f.lcm = lcm_create(url);
  if (f.lcm == NULL) {
    fprintf(stderr, "ahhs-example-firmware: cannot open the bus %s\n", url);
    return 1;
  }
  char channel[256];
  snprintf(channel, sizeof channel, "%s/SIM/CLOCK", arena);
  ahhs_sim_clock_t_subscription_t* clock_sub =
      ahhs_sim_clock_t_subscribe(f.lcm, channel, on_clock, &f);
  snprintf(channel, sizeof channel, "%s/MODULE%d/HINGE", arena, id);
  ahhs_hinge_command_t_subscription_t* hinge_sub =
      ahhs_hinge_command_t_subscribe(f.lcm, channel, on_hinge, &f);
  snprintf(f.sensors_channel, sizeof f.sensors_channel, "%s/MODULE%d/SENSORS", arena, id);
  ahhs_module_sensors_t_subscription_t* sensors_sub =
      ahhs_module_sensors_t_subscribe(f.lcm, f.sensors_channel, on_sensors, &f);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  const double end = now_s() + seconds;
  while (!stop_requested && (seconds == 0 || now_s() < end)) lcm_handle_timeout(f.lcm, 100);
  printf(
      "firmware of module %d: %ld readings sent, %ld commands applied, %ld dropped, %ld "
      "readings of others on %s\n",
      id, f.readings, f.commands, f.dropped_commands, f.foreign_readings, f.sensors_channel);
  ahhs_sim_clock_t_unsubscribe(f.lcm, clock_sub);
  ahhs_hinge_command_t_unsubscribe(f.lcm, hinge_sub);
  ahhs_module_sensors_t_unsubscribe(f.lcm, sensors_sub);
  lcm_destroy(f.lcm);
  return 0;
}
