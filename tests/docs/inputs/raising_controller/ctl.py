# docs/explanation/navigation.md: a controller that raises in observe.
import math


class Controller:
    def __init__(self, robot, route):
        self.route = route

    def observe(self, scan, odometry, time):
        parameters = {}
        return parameters["speed"], math.radians(0.0)
