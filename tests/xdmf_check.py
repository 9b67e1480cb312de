#!/usr/bin/env python3
"""Reads an XDMF file of ssstar with VTK's XDMF reader (vtkXdmfReader, what ParaView uses) and prints, as JSON, its
time steps and, per time step and grid, the number of points and cells and the mean of each point array per
component (and of each cell array, "cell_means"): tests/suite_loadpath.py and tests/suite_displacement.py compare
them with the HDF5 file. Needs a Python with VTK (pip install vtk).

  xdmf_check.py FILE.xmf"""
import json
import sys

import vtk
from vtk.util.numpy_support import vtk_to_numpy


def main():
    reader = vtk.vtkXdmfReader()
    reader.SetFileName(sys.argv[1])
    reader.UpdateInformation()
    info = reader.GetOutputInformation(0)
    key = vtk.vtkStreamingDemandDrivenPipeline.TIME_STEPS()
    times = [info.Get(key, i) for i in range(info.Length(key))] if info.Has(key) else [None]
    steps = []
    for t in times:
        if t is None:
            reader.Update()
        else:
            reader.UpdateTimeStep(t)
        out = reader.GetOutputDataObject(0)
        grids = {}
        for b in range(out.GetNumberOfBlocks()):
            block = out.GetBlock(b)
            name = out.GetMetaData(b).Get(vtk.vtkCompositeDataSet.NAME())
            data = block.GetPointData()
            arrays = {}
            for i in range(data.GetNumberOfArrays()):
                a = vtk_to_numpy(data.GetArray(i)).astype(float)
                arrays[data.GetArrayName(i)] = a.reshape(len(a), -1).mean(axis=0).tolist()
            cells = block.GetCellData()
            cell_means = {}
            for i in range(cells.GetNumberOfArrays()):
                a = vtk_to_numpy(cells.GetArray(i)).astype(float)
                cell_means[cells.GetArrayName(i)] = a.reshape(len(a), -1).mean(axis=0).tolist()
            grids[name] = {"points": block.GetNumberOfPoints(), "cells": block.GetNumberOfCells(), "means": arrays, "cell_means": cell_means}
        steps.append({"time": t, "grids": grids})
    print(json.dumps(steps))


if __name__ == "__main__":
    main()
