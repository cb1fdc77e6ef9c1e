/* A small file system emulated in one folder, for the full-disk fault tests
 * where the test may not mount a tmpfs (tests/faults/run_fault.py). Preloaded
 * into boomdyn (LD_PRELOAD) with
 *   BOOMDYN_SMALL_DISK_DIR=<folder>  BOOMDYN_SMALL_DISK_BYTES=<capacity>
 * it makes statvfs() of that folder report the capacity less the sizes of the
 * files in it, and write()/pwrite() to a file there fail with ENOSPC once the
 * file's new end would exceed what is left. Nothing else changes. */
#define _GNU_SOURCE
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

static const char *folder(void) { return getenv("BOOMDYN_SMALL_DISK_DIR"); }

static long long capacity(void)
{
  const char *c = getenv("BOOMDYN_SMALL_DISK_BYTES");
  return c ? atoll(c) : 0;
}

/* Bytes used in the folder: the sizes of its regular files. */
static long long used(void)
{
  long long total = 0;
  DIR *d = opendir(folder());
  if (!d) return 0;
  struct dirent *e;
  char path[PATH_MAX];
  while ((e = readdir(d))) {
    struct stat s;
    snprintf(path, sizeof path, "%s/%s", folder(), e->d_name);
    if (stat(path, &s) == 0 && S_ISREG(s.st_mode)) total += (long long)s.st_size;
  }
  closedir(d);
  return total;
}

static int inFolder(const char *path)
{
  char real[PATH_MAX], base[PATH_MAX];
  if (!folder() || !realpath(folder(), base)) return 0;
  if (!realpath(path, real)) return 0;
  const size_t n = strlen(base);
  return strncmp(real, base, n) == 0 && (real[n] == '/' || real[n] == '\0');
}

/* Would writing count bytes at offset to fd grow the folder beyond its capacity? */
static int wouldOverflow(int fd, size_t count, off_t offset)
{
  char link[64], path[PATH_MAX];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof path - 1);
  if (n <= 0) return 0;
  path[n] = '\0';
  if (!inFolder(path)) return 0;
  struct stat s;
  if (fstat(fd, &s) != 0) return 0;
  const long long end = (long long)offset + (long long)count;
  const long long growth = end > s.st_size ? end - s.st_size : 0;
  return used() + growth > capacity();
}

ssize_t pwrite(int fd, const void *buf, size_t count, off_t offset)
{
  static ssize_t (*real)(int, const void *, size_t, off_t);
  if (!real) real = (ssize_t(*)(int, const void *, size_t, off_t))dlsym(RTLD_NEXT, "pwrite");
  if (wouldOverflow(fd, count, offset)) {
    errno = ENOSPC;
    return -1;
  }
  return real(fd, buf, count, offset);
}

ssize_t write(int fd, const void *buf, size_t count)
{
  static ssize_t (*real)(int, const void *, size_t);
  if (!real) real = (ssize_t(*)(int, const void *, size_t))dlsym(RTLD_NEXT, "write");
  if (fd > 2 && wouldOverflow(fd, count, lseek(fd, 0, SEEK_CUR))) {
    errno = ENOSPC;
    return -1;
  }
  return real(fd, buf, count);
}

int statvfs(const char *path, struct statvfs *buf)
{
  static int (*real)(const char *, struct statvfs *);
  if (!real) real = (int (*)(const char *, struct statvfs *))dlsym(RTLD_NEXT, "statvfs");
  const int status = real(path, buf);
  if (status == 0 && inFolder(path)) {
    const long long left = capacity() - used();
    buf->f_bavail = buf->f_bfree = left > 0 ? (fsblkcnt_t)(left / (long long)buf->f_frsize) : 0;
  }
  return status;
}
