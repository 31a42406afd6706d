/* insn_count: a QEMU TCG plugin that counts the guest instructions executed between two marker
 * functions, for reconfig's firmware (firmware/src/m7/measure.rs: reconfig_measure_start/_stop).
 *
 * Arguments: start=<address>,stop=<address> (hex with 0x, or decimal), the markers' addresses
 * from the ELF symbol table (the Thumb bit is ignored). Every execution of the stop marker prints
 *     reconfig-insns measurement=<k> instructions=<n>
 * through qemu_plugin_outs (shown with `-d plugin`, on stderr or in the `-D` file), where n counts
 * every instruction executed from the first instruction of the start marker up to, not
 * including, the first instruction of the stop marker: the solve plus the constant few
 * instructions of the start marker and the call sequence. Single vCPU only (the mps2 boards).
 *
 * Build: gcc -shared -fPIC -O2 -o libinsn_count.so insn_count.c
 * Use:   qemu-system-arm ... -plugin ./libinsn_count.so,start=0x...,stop=0x... -d plugin
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qemu_plugin_api.h"

QEMU_PLUGIN_EXPORT int qemu_plugin_version = 1;

static uint64_t executed;  /* every instruction, by an inline add */
static uint64_t at_start;  /* `executed` when the start marker last ran */
static uint64_t start_addr, stop_addr;
static unsigned measurement;

static void on_start(unsigned int vcpu_index, void *userdata)
{
    (void)vcpu_index;
    (void)userdata;
    at_start = executed;
}

static void on_stop(unsigned int vcpu_index, void *userdata)
{
    char line[96];
    (void)vcpu_index;
    (void)userdata;
    snprintf(line, sizeof line, "reconfig-insns measurement=%u instructions=%" PRIu64 "\n",
             measurement, executed - at_start);
    measurement++;
    qemu_plugin_outs(line);
}

static void on_translate(qemu_plugin_id_t id, struct qemu_plugin_tb *tb)
{
    size_t n = qemu_plugin_tb_n_insns(tb);
    (void)id;
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t vaddr = qemu_plugin_insn_vaddr(insn);
        /* The callbacks run before this instruction's own inline add, so `executed` counts the
         * instructions before it. */
        if (vaddr == start_addr) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_start, QEMU_PLUGIN_CB_NO_REGS, NULL);
        } else if (vaddr == stop_addr) {
            qemu_plugin_register_vcpu_insn_exec_cb(insn, on_stop, QEMU_PLUGIN_CB_NO_REGS, NULL);
        }
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &executed, 1);
    }
}

static int parse_address(const char *arg, const char *key, uint64_t *out)
{
    size_t len = strlen(key);
    char *end;
    if (strncmp(arg, key, len) != 0 || arg[len] != '=') {
        return 0;
    }
    *out = strtoull(arg + len + 1, &end, 0) & ~(uint64_t)1; /* drop the Thumb bit */
    return *end == '\0';
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc,
                                           char **argv)
{
    int have_start = 0, have_stop = 0;
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (parse_address(argv[i], "start", &start_addr)) {
            have_start = 1;
        } else if (parse_address(argv[i], "stop", &stop_addr)) {
            have_stop = 1;
        } else {
            fprintf(stderr, "insn_count: unknown argument %s (want start=ADDR,stop=ADDR)\n", argv[i]);
            return -1;
        }
    }
    if (!have_start || !have_stop) {
        fprintf(stderr, "insn_count: need start=ADDR,stop=ADDR\n");
        return -1;
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, on_translate);
    return 0;
}
