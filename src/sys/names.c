/* Names the user may have misspelt: the distance the refusals use to name the nearest known option or group */
#include <ctype.h>
#include "names.h"

/* The optimal string alignment distance (Levenshtein with transpositions), case-insensitive */
PetscInt SSStarNameDistance(const char a[], size_t la, const char b[], size_t lb)
{
  PetscInt d[3][257]; /* rows i-2, i-1, i; option names are shorter */

  if (la > 256 || lb > 256) return PETSC_MAX_INT;
  for (size_t j = 0; j <= lb; j++) d[1][j] = (PetscInt)j;
  for (size_t i = 1; i <= la; i++) {
    PetscInt *cur = d[(i + 1) % 3], *prev = d[i % 3], *prev2 = d[(i + 2) % 3];

    cur[0] = (PetscInt)i;
    for (size_t j = 1; j <= lb; j++) {
      const PetscInt cost = tolower((unsigned char)a[i - 1]) != tolower((unsigned char)b[j - 1]);

      cur[j] = PetscMin(PetscMin(prev[j] + 1, cur[j - 1] + 1), prev[j - 1] + cost);
      if (i > 1 && j > 1 && tolower((unsigned char)a[i - 1]) == tolower((unsigned char)b[j - 2]) && tolower((unsigned char)a[i - 2]) == tolower((unsigned char)b[j - 1])) cur[j] = PetscMin(cur[j], prev2[j - 2] + 1);
    }
  }
  return d[(la + 1) % 3][lb];
}
